#!/usr/bin/env bash
# The thermal cases of Code_Aster's 2025 corpus (../shared/corpus/astest-2025): every `.export` whose
# command files call THER_LINEAIRE or THER_NON_LINE, run unmodified (`aster run CASE.export`, two at a
# time, 120 s each), with the outcome of each and what stops the rest, grouped (numbers and quoted names
# folded so that like reasons count together). docs/corpus.md quotes its tables.
#
#   scripts/corpus_heat.sh             # the two tables
#   KEEP=1 scripts/corpus_heat.sh      # and keep the runs' folders (printed)
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
CORPUS=${CORPUS:-$ROOT/../shared/corpus/astest-2025}
[ -d "$CORPUS" ] || { echo "corpus_heat: $CORPUS is absent" >&2; exit 1; }
cargo build --release -q --bin aster
OUT=$(mktemp -d)
[ -n "${KEEP:-}" ] && echo "runs in $OUT" || trap 'rm -rf "$OUT"' EXIT
cd "$CORPUS"
cases=$(grep -l -E "THER_LINEAIRE|THER_NON_LINE" -- *.comm *.com[0-9] 2>/dev/null | sed -E 's/\.(comm|com[0-9])$//' | sort -u)
run() {
    c=$1
    timeout 120 "$ROOT/target/release/aster" run "$CORPUS/$c.export" --out "$OUT/$c" >"$OUT/$c.log" 2>&1 || true
    v=$(grep -o "DIAGNOSTIC JOB : .*" "$OUT/$c.log" | tail -1 | sed 's/DIAGNOSTIC JOB : //')
    err=$(grep -m1 -E "^ ?<F>|panicked" "$OUT/$c.log" | sed -E 's/^ ?<F> [^:]+:[0-9]+:[0-9]+: //; s/^ ?<F> //' || true)
    echo "$c|${v:-TIME_LIMIT}|$err"
}
export -f run
export ROOT CORPUS OUT
echo "$cases" | xargs -P 2 -I{} bash -c 'run {}' >"$OUT/results.txt"
total=$(wc -l <"$OUT/results.txt")
ok=$(grep -c "|OK|" "$OUT/results.txt" || true)
missing=$(grep -c "does not exist" "$OUT/results.txt" || true)
echo "thermal cases: $total; every check OK: $ok; a data file the .export names is not in the corpus: $missing"
echo
echo "| cases | outcome |"
echo "|---:|---|"
cut -d'|' -f2 "$OUT/results.txt" | sort | uniq -c | sort -rn | awk '{ n = $1; $1 = ""; sub(/^ /, ""); printf "| %d | %s |\n", n, $0 }'
echo
echo "| cases | what stops them (first error) |"
echo "|---:|---|"
grep -v "|OK|" "$OUT/results.txt" | grep -v "does not exist" | cut -d'|' -f3- \
    | sed -E "s/'[^']*'/'…'/g; s/[0-9]+/N/g" | cut -c1-110 | sort | uniq -c | sort -rn \
    | awk '{ n = $1; $1 = ""; sub(/^ /, ""); if ($0 == "") $0 = "(a NOOK check: the run ends, a check fails)"; printf "| %d | %s |\n", n, $0 }'
echo
echo "OK: $(grep "|OK|" "$OUT/results.txt" | cut -d'|' -f1 | tr '\n' ' ')"
