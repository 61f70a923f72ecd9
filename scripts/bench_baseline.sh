#!/usr/bin/env bash
# Wall time of this build against a baseline build of an earlier commit, measured in one run, alternating
# the two binaries: the legacy suite ../shared/astest (`aster suite -j 1`) and comm/junction_2d.comm on an
# N x N QUAD8 box (N = 128 by default). Prints the best of REPEAT runs of each and the ratio new / base.
#
#   scripts/bench_baseline.sh 33bf48c                 # builds the baseline in a temporary worktree
#   BASE_BIN=/path/to/aster scripts/bench_baseline.sh  # or uses a binary built already
#   N=64 REPEAT=3 scripts/bench_baseline.sh 33bf48c
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
cd "$ROOT"
N=${N:-128}
REPEAT=${REPEAT:-2}
cargo build --release -q --bin aster
NEW=$ROOT/target/release/aster
WORK=$(mktemp -d)
cleanup() {
    if [ -n "${TREE:-}" ]; then git worktree remove --force "$TREE" >/dev/null 2>&1 || true; fi
    rm -rf "$WORK"
}
trap cleanup EXIT
if [ -n "${BASE_BIN:-}" ]; then
    BASE=$BASE_BIN
else
    COMMIT=${1:?"usage: scripts/bench_baseline.sh COMMIT (or BASE_BIN=... scripts/bench_baseline.sh)"}
    TREE=$WORK/base
    git worktree add -q --detach "$TREE" "$COMMIT"
    (cd "$TREE" && cargo build --release -q --bin aster)
    BASE=$TREE/target/release/aster
fi
"$NEW" mesh box --cell QUAD8 --n "$N,$N" --size 10,10 -o "$WORK/m.med" >/dev/null

secs() { # command... -> wall seconds
    local t0 t1
    t0=$(date +%s.%N)
    "$@" >/dev/null 2>&1 || true
    t1=$(date +%s.%N)
    awk -v a="$t0" -v b="$t1" 'BEGIN { print b - a }'
}
best() { # current best, new value
    if [ -z "$1" ] || awk -v a="$2" -v b="$1" 'BEGIN { exit !(a < b) }'; then echo "$2"; else echo "$1"; fi
}
suite_new="" suite_base="" junc_new="" junc_base=""
for _ in $(seq "$REPEAT"); do
    for which in base new; do
        bin=$BASE
        [ "$which" = new ] && bin=$NEW
        s=$(secs "$bin" suite ../shared/astest -j 1 --out "$WORK/suite-$which")
        j=$(secs "$bin" run comm/junction_2d.comm --unit "20=$WORK/m.med" --unit "80=$WORK/r-$which.rmed" \
            --out "$WORK/j-$which" -q)
        if [ "$which" = new ]; then
            suite_new=$(best "$suite_new" "$s")
            junc_new=$(best "$junc_new" "$j")
        else
            suite_base=$(best "$suite_base" "$s")
            junc_base=$(best "$junc_base" "$j")
        fi
    done
done
printf "| run | baseline | this build | ratio |\n|---|---:|---:|---:|\n"
printf "| aster suite ../shared/astest -j 1 | %.2f s | %.2f s | %.2f |\n" "$suite_base" "$suite_new" \
    "$(awk -v a="$suite_new" -v b="$suite_base" 'BEGIN { print a / b }')"
printf "| junction_2d N=%s | %.2f s | %.2f s | %.2f |\n" "$N" "$junc_base" "$junc_new" \
    "$(awk -v a="$junc_new" -v b="$junc_base" 'BEGIN { print a / b }')"
