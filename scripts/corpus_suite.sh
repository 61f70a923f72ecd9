#!/bin/sh
# Run every export of Code_Aster's 2025 corpus (../shared/corpus/astest-2025) with `aster suite`, niced,
# two at a time: the per-case table, the summary of what stops the cases, and in OUT (default
# aster-suite-corpus) junit.xml, stops.csv, suite.json and passing.txt (the passing cases in the format
# of tests/corpus_passing.txt). Extra arguments go to `aster suite` (e.g. --list FILE for a subset).
set -e
cd "$(dirname "$0")/.."
out=${OUT:-aster-suite-corpus}
cargo build --release --quiet
start=$(date +%s)
nice -n 10 target/release/aster suite ../shared/corpus/astest-2025 -j 2 --out "$out" "$@" > "$out.txt" || true
echo "corpus suite: $(( $(date +%s) - start )) s; table in $out.txt"
sed -n '/cases:/,$p' "$out.txt" | tail -60
