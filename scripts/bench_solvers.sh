#!/usr/bin/env bash
# Benchmark of the solver against GetFEM (issue 13): in one run, the 2D junction scene (comm/junction_2d.comm on
# N x N QUAD8 boxes of size 10 x 10) and its GetFEM peer (../shared/peers/getfem_junction2d.py, sequential
# MUMPS), one after the other, then 3D HEXA20 statics against GetFEM through scripts/bench_statics.sh.
#
#   scripts/bench_solvers.sh                               # junction N = 160 320, 3D 40x26x14 (~193 k dofs)
#   BENCH_N="32 64" BENCH_3D="none" scripts/bench_solvers.sh   # quick smoke run
#   BENCH_3D="40,26,14 46,30,16" scripts/bench_solvers.sh  # 3D at ~193 k and ~289 k dofs (GetFEM peaks
#                                                          # near 14 GiB at the larger size)
#
# Junction columns: unknowns solved, our wall time and peak memory (/usr/bin/time -v), the solver line of the
# log (method, ordering, factorization seconds), our lip error (largest |error| of the interface nodes over U),
# GetFEM's setup + solve (its own timers, interpreter start-up excluded as in its README) and its error, the
# ratio of the two times, and the 1-minute load average when the case started. Reports, never asserts, times.
set -euo pipefail

ROOT=$(cd "$(dirname "$0")/.." && pwd)
cd "$ROOT"
NS=${BENCH_N:-160 320}
N3D=${BENCH_3D:-40,26,14}
PEER=${BENCH_PEER:-$ROOT/../shared/peers/getfem_junction2d.py}
PY=/usr/bin/python3
export OPENBLAS_NUM_THREADS=${BENCH_GETFEM_THREADS:-1}
cargo build --release -q
ASTER=$ROOT/target/release/aster
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT

. "$ROOT/scripts/bench_lib.sh"

echo "## junction_2d against GetFEM (OPENBLAS_NUM_THREADS=$OPENBLAS_NUM_THREADS for GetFEM)"
echo
echo "| N | solved | ours wall (s) | ours peak (GiB) | factor. + solves (s) | solver | lip err / U | GetFEM setup + solve (s) | GetFEM peak (GiB) | GetFEM err | ours / GetFEM | load |"
echo "|---|---:|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|"
for n in $NS; do
    d=$WORK/n$n
    mkdir -p "$d"
    "$ASTER" mesh box --cell QUAD8 --n "$n,$n" --size 10,10 -o "$d/m.med" >/dev/null
    l=$(load)
    /usr/bin/time -v -o "$d/aster.time" "$ASTER" run comm/junction_2d.comm --unit 20="$d/m.med" --unit 80="$d/r.rmed" \
        --out "$d" -q >/dev/null 2>&1 || true
    mess=$d/junction_2d.mess
    solved=$(grep -m1 "unknowns  :" "$mess" | sed 's/.*, \([0-9]*\) solved.*/\1/')
    fact=$(grep -m1 "    time      :" "$mess" | sed 's/.*factorization and solves \([0-9.]*\) s.*/\1/')
    solver=$(grep -m1 -A1 "    solver    :" "$mess" | tail -1 | sed 's/^ *//; s/, factor .*//; s/ (LDLT refinement failed: LU)/ (fallback)/')
    err=$({ grep -E "^ +(NOOK|OK) +ANALYTIQUE +ERR_" "$mess" || true; } |
        awk '{v=$5; if (v<0) v=-v; if (v>m) m=v} END {if (m=="") print "-"; else printf "%.1e", m/1e-4}')
    diag=$(grep -m1 "DIAGNOSTIC JOB" "$mess" | awk '{print $NF}')
    /usr/bin/time -v -o "$d/gf.time" "$PY" "$PEER" "$n" xfem >"$d/gf.out" 2>"$d/gf.err" || true
    gsetup=$(sed -n 's/.*setup=\([0-9.]*\)s.*/\1/p' "$d/gf.out")
    gsolve=$(sed -n 's/.*solve=\([0-9.]*\)s.*/\1/p' "$d/gf.out")
    gerr=$(sed -n 's/.*err_nodes=\([0-9.e+-]*\).*/\1/p' "$d/gf.out")
    gtot=$(awk -v a="${gsetup:-0}" -v b="${gsolve:-0}" 'BEGIN { printf "%.2f", a + b }')
    ours=$(wall "$d/aster.time")
    ratio=$(awk -v a="$ours" -v b="$gtot" 'BEGIN { if (b > 0) printf "%.2f", a / b; else print "-" }')
    echo "| $n | $solved | $ours | $(rss "$d/aster.time") | $fact | $solver ($diag) | $err | $gtot | $(rss "$d/gf.time") | $gerr | $ratio | $l |"
done

for s in $N3D; do
    [ "$s" = none ] && continue
    echo
    echo "## 3D HEXA20 statics $s against GetFEM (load $(load) at start)"
    echo
    BENCH_2D=8,4 BENCH_3D=$s bash scripts/bench_statics.sh
done
