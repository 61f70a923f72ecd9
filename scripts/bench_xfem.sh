#!/usr/bin/env bash
# Benchmark of the X-FEM cohesive-interface pipeline (issue 5, acceptance point 6): wtnv149a and wtnv149b end
# to end (read in place from ../shared/astest), then our 2D scene comm/junction_2d.comm on meshes refined up
# to ~300 k unknowns; wall time split by stage, read from the .mess file of each run.
#
#   scripts/bench_xfem.sh                       # N = 8 32 64 128 224 (QUAD8 cells per side)
#   BENCH_XFEM_N="8 16" scripts/bench_xfem.sh   # quick smoke run
#
# Columns: unknowns (all, and solved after elimination), then seconds: MODI_MODELE_XFEM (TOPOSE cutting,
# regions, enrichment sets), STAT_NON_LINE split into element matrices / assembly / factorization+solves /
# total, POST_MAIL_XFEM, POST_CHAM_XFEM, the whole run (wall, /usr/bin/time) with peak memory, the largest
# error of the lip displacements against the analytic field (scene runs, relative to U) and the verdict.
# Exits non-zero if a run stops on an error; a NOOK is reported in the table (the scene's checks are tuned
# for its own 8x8 mesh).
set -euo pipefail

ROOT=$(cd "$(dirname "$0")/.." && pwd)
cd "$ROOT"
NS=${BENCH_XFEM_N:-8 32 64 128 224}
cargo build --release -q
ASTER=$ROOT/target/release/aster
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT

elapsed() { # command name, mess file -> seconds of its first occurrence
    grep -m1 "End of command #[0-9]* $1 " "$2" | sed 's/.*elapsed \([0-9.]*\) s.*/\1/'
}
snl() { # field of the STAT_NON_LINE time line: elements|assembly|factorization|total
    grep -m1 "    time      :" "$2" | sed "s/.*$1[a-z ]* \([0-9.]*\) s.*/\1/"
}
row() { # label, mess, time -v output
    local mess=$2 tv=$3
    local unk solved wall rss err diag
    err=$({ grep -E "^ +(NOOK|OK) +ANALYTIQUE +ERR_" "$mess" || true; } | awk '{v=$5; if (v<0) v=-v; if (v>m) m=v} END {if (m=="") print "-"; else printf "%.1e", m/1e-4}')
    diag=$(grep -m1 "DIAGNOSTIC JOB" "$mess" | awk '{print $NF}')
    unk=$(grep -m1 "unknowns  :" "$mess" | sed 's/.*unknowns  : \([0-9]*\) .*/\1/')
    solved=$(grep -m1 "unknowns  :" "$mess" | sed 's/.*, \([0-9]*\) solved.*/\1/')
    wall=$(grep "Elapsed (wall clock)" "$tv" | awk '{print $NF}')
    rss=$(grep "Maximum resident" "$tv" | awk '{printf "%.0f", $NF/1024}')
    printf "| %-17s | %8s | %8s | %8s | %8s | %8s | %8s | %8s | %8s | %8s | %8s | %6s | %8s | %-15s |\n" "$1" "$unk" "$solved" \
        "$(elapsed MODI_MODELE_XFEM "$mess")" "$(snl elements "$mess")" "$(snl assembly "$mess")" \
        "$(snl factorization "$mess")" "$(snl total "$mess")" "$(elapsed POST_MAIL_XFEM "$mess")" \
        "$(elapsed POST_CHAM_XFEM "$mess")" "$wall" "$rss" "$err" "$diag"
}
run() { # label, export-or-comm, extra args...
    local label=$1 input=$2
    shift 2
    local out=$WORK/$label
    mkdir -p "$out"
    /usr/bin/time -v "$ASTER" run "$input" --out "$out" -q "$@" >"$out/stdout" 2>"$out/time" || true
    local mess
    mess=$(ls "$out"/*.mess)
    if grep -q "DIAGNOSTIC JOB : <F>" "$mess"; then
        echo "run $label failed:" >&2
        tail -5 "$mess" >&2
        exit 1
    fi
    row "$label" "$mess" "$out/time"
}

echo "| case              | unknowns |   solved | MODI_XFM | elements | assembly | factor.  | SNL tot. | POST_MAIL| POST_CHAM| wall     | MiB    | lip err. | verdict         |"
echo "|-------------------|----------|----------|----------|----------|----------|----------|----------|----------|----------|----------|--------|----------|-----------------|"
for t in wtnv149a wtnv149b; do
    if [ -f ../shared/astest/$t.export ]; then
        run "$t" ../shared/astest/$t.export
    fi
done
for n in $NS; do
    "$ASTER" mesh box --cell QUAD8 --n "$n,$n" --size 10,10 -o "$WORK/m$n.med" >/dev/null
    run "junction_2d N=$n" comm/junction_2d.comm --unit "20=$WORK/m$n.med" --unit "80=$WORK/r$n.rmed"
done
