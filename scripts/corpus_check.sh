#!/usr/bin/env bash
# How much of Code_Aster's 2025 verification corpus (../shared/corpus/astest-2025) aster-rs parses and
# validates against its catalogue (`aster check`: no computation), with the most frequent reasons for a
# refusal, numbers and quoted names folded so that like reasons count together.
#
#   scripts/corpus_check.sh            # counts and the 20 most frequent reasons
#   TOP=40 scripts/corpus_check.sh
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
CORPUS=${CORPUS:-$ROOT/../shared/corpus/astest-2025}
TOP=${TOP:-20}
[ -d "$CORPUS" ] || { echo "corpus_check: $CORPUS is absent" >&2; exit 1; }
cargo build --release -q --bin aster
OUT=$(mktemp)
trap 'rm -f "$OUT"' EXIT
cd "$CORPUS"
ls -- *.comm | xargs -n 200 "$ROOT/target/release/aster" check >"$OUT" 2>&1 || true
total=$(ls -- *.comm | wc -l)
ok=$(grep -c ": OK (" "$OUT" || true)
echo "command files: $total, passing aster check: $ok"
echo
echo "| files | first refusal |"
echo "|---:|---|"
grep -v ": OK (" "$OUT" | grep -v "file(s) failed the check" | sed -E 's/^[^:]+:[0-9]+:[0-9]+: //' \
    | sed -E "s/'[^']*'/'…'/g; s/[0-9]+/N/g" | cut -c1-100 | sort | uniq -c | sort -rn | head -"$TOP" \
    | awk '{ n = $1; $1 = ""; sub(/^ /, ""); printf "| %d | %s |\n", n, $0 }'
