#!/usr/bin/env bash
# Benchmark of linear elastic statics (issue 4, acceptance point 4): aster-rs against GetFEM, same machine,
# same run.
#
#   scripts/bench_statics.sh            # 2D QUAD8 580x290 (~1.01 M dofs), 3D HEXA20 40x26x14 (~0.19 M dofs)
#   BENCH_2D=40,20 BENCH_3D=6,4,2 scripts/bench_statics.sh   # quick smoke run
#
# Environment:
#   BENCH_2D=NX,NY          QUAD8 cells of the 2 x 1 plane-strain block (default 580,290)
#   BENCH_3D=NX,NY,NZ       HEXA20 cells of the 3 x 2 x 1 block (default 40,26,14: ~193 k dofs,
#                           which keeps the script near 6 min here; 46,30,16 gives ~289 k dofs but
#                           ~12 min and ~14 GiB peak); BENCH_3D=none skips 3D
#   BENCH_GETFEM_THREADS=N  OpenBLAS threads for GetFEM/MUMPS (default 1: sequential MUMPS, as the issues measure it)
#   BENCH_DIR=PATH          work folder (default: a fresh temp folder, removed at the end)
#
# For each case: `aster mesh box` writes the mesh, a .comm (clamp/symmetry + uniform traction, D_PLAN or 3D,
# CALC_CHAMP SIGM_NOEU as the post-processing phase, one TEST_RESU against the analytic displacement) runs
# under `/usr/bin/time -v` (wall time, peak RSS), the phase times are read from the .mess file, then
# scripts/bench_statics_getfem.py solves the same problem with GetFEM (python3-getfem, MUMPS) under
# `/usr/bin/time -v` too. Prints one table; exits non-zero if a run or a check fails.
set -euo pipefail

ROOT=$(cd "$(dirname "$0")/.." && pwd)
cd "$ROOT"
N2D=${BENCH_2D:-580,290}
N3D=${BENCH_3D:-40,26,14}
GF_THREADS=${BENCH_GETFEM_THREADS:-1}
PY=/usr/bin/python3

if ! "$PY" -c 'import getfem' 2>/dev/null; then
    echo "python3-getfem is missing: installing it (apt-get)" >&2
    apt-get install -y python3-getfem >/dev/null 2>&1 || { apt-get update >/dev/null && apt-get install -y python3-getfem >/dev/null; }
fi

echo "== cargo build --release" >&2
cargo build --release 2>&1 | tail -1 >&2
ASTER="$ROOT/target/release/aster"

if [ -n "${BENCH_DIR:-}" ]; then
    WORK=$BENCH_DIR
    mkdir -p "$WORK"
else
    WORK=$(mktemp -d /tmp/bench_statics.XXXXXX)
    trap 'rm -rf "$WORK"' EXIT
fi
RESULTS="$WORK/results.txt"
: >"$RESULTS"

# Wall time (s) and peak RSS (MiB) from a `/usr/bin/time -v` log.
time_fields() {
    awk -F': ' '
        /Elapsed \(wall clock\)/ { n = split($2, t, ":"); s = 0; for (i = 1; i <= n; i++) s = s * 60 + t[i]; wall = s }
        /Maximum resident set size/ { rss = $2 / 1024 }
        END { printf "wall=%.3f rss=%.0f", wall, rss }' "$1"
}

write_comm_2d() {
    cat >"$1" <<'EOF'
# bench_statics: plane-strain QUAD8 block 2 x 1 under a uniform traction (see comm/block_tension_2d.comm).
DEBUT(CODE="OUI")
E = 210000.0
NU = 0.3
P = 100.0
LX, LY = 2.0, 1.0
MA = LIRE_MAILLAGE(FORMAT="MED", UNITE=20)
MA = DEFI_GROUP(reuse=MA, MAILLAGE=MA, CREA_GROUP_NO=_F(NOM="C", INTERSEC=("HAUT", "DROITE")))
MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="D_PLAN"))
ACIER = DEFI_MATERIAU(ELAS=_F(E=E, NU=NU))
CHMAT = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT="OUI", MATER=ACIER))
BLOC = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=(_F(GROUP_NO="GAUCHE", DX=0.0), _F(GROUP_NO="BAS", DY=0.0)))
TRAC = AFFE_CHAR_MECA(MODELE=MO, PRES_REP=_F(GROUP_MA="DROITE", PRES=-P))
RESU = MECA_STATIQUE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=(_F(CHARGE=BLOC), _F(CHARGE=TRAC)))
RESU = CALC_CHAMP(reuse=RESU, RESULTAT=RESU, CONTRAINTE="SIGM_NOEU")
UX = (1 - NU**2) * P * LX / E
UY = -NU * (1 + NU) * P * LY / E
TEST_RESU(
    RESU=(
        _F(RESULTAT=RESU, NUME_ORDRE=1, NOM_CHAM="DEPL", GROUP_NO="C", NOM_CMP="DX",
           VALE_CALC=UX, VALE_REFE=UX, REFERENCE="ANALYTIQUE", PRECISION=1.0e-6),
        _F(RESULTAT=RESU, NUME_ORDRE=1, NOM_CHAM="DEPL", GROUP_NO="C", NOM_CMP="DY",
           VALE_CALC=UY, VALE_REFE=UY, REFERENCE="ANALYTIQUE", PRECISION=1.0e-6),
    )
)
FIN()
EOF
}

write_comm_3d() {
    cat >"$1" <<'EOF'
# bench_statics: HEXA20 block 3 x 2 x 1, symmetry planes, uniform traction (see comm/block_tension_3d.comm).
DEBUT(CODE="OUI")
E = 70000.0
NU = 0.25
F = 50.0
LX, LY, LZ = 3.0, 2.0, 1.0
MA = LIRE_MAILLAGE(FORMAT="MED", UNITE=20)
DEFI_GROUP(reuse=MA, MAILLAGE=MA, CREA_GROUP_NO=_F(NOM="P", INTERSEC=("XMAX", "YMAX", "ZMAX")))
MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="3D"))
ALU = DEFI_MATERIAU(ELAS=_F(E=E, NU=NU))
CHMAT = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT="OUI", MATER=ALU))
SYME = AFFE_CHAR_MECA(
    MODELE=MO, DDL_IMPO=(_F(GROUP_NO="XMIN", DX=0.0), _F(GROUP_NO="YMIN", DY=0.0), _F(GROUP_NO="ZMIN", DZ=0.0))
)
TRAC = AFFE_CHAR_MECA(MODELE=MO, FORCE_FACE=_F(GROUP_MA="XMAX", FX=F))
RESU = MECA_STATIQUE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=(_F(CHARGE=SYME), _F(CHARGE=TRAC)))
CALC_CHAMP(reuse=RESU, RESULTAT=RESU, CONTRAINTE="SIGM_NOEU")
expected = {"DX": F * LX / E, "DY": -NU * F * LY / E, "DZ": -NU * F * LZ / E}
TEST_RESU(
    RESU=[
        _F(RESULTAT=RESU, NUME_ORDRE=1, NOM_CHAM="DEPL", GROUP_NO="P", NOM_CMP=c,
           VALE_CALC=v, VALE_REFE=v, REFERENCE="ANALYTIQUE", PRECISION=1.0e-6)
        for c, v in expected.items()
    ]
)
FIN()
EOF
}

# run_case NAME CELL N SIZE DIMFLAG
run_case() {
    local name=$1 cell=$2 n=$3 size=$4 gcase=$5
    local dir="$WORK/$name"
    mkdir -p "$dir"
    echo "== $name: $cell cells $n (load: $(cut -d' ' -f1-3 /proc/loadavg))" >&2
    local t0 t1
    t0=$(date +%s.%N)
    "$ASTER" mesh box --cell "$cell" --n "$n" --size "$size" -o "$dir/mesh.med" >"$dir/mesh.log"
    t1=$(date +%s.%N)
    local tgen
    tgen=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.3f", b - a }')
    "write_comm_$gcase" "$dir/case.comm"
    local rc=0 load
    load=$(cut -d' ' -f1 /proc/loadavg)
    /usr/bin/time -v -o "$dir/aster.time" "$ASTER" run "$dir/case.comm" --unit 20="$dir/mesh.med" --out "$dir" -q \
        >"$dir/aster.out" 2>&1 || rc=$?
    local mess="$dir/case.mess"
    # Phase times from the message file.
    local phases
    phases=$(awk '
        /# End of command #[0-9]+ LIRE_MAILLAGE / { mesh += $(NF - 1) }
        /# End of command #[0-9]+ CALC_CHAMP / { calc += $(NF - 1) }
        /linear statics \(/ { for (i = 1; i <= NF; i++) if ($i == "unknowns,") nd = $(i - 1) }
        /^ *time: numbering/ {
            gsub(",", "")
            for (i = 1; i <= NF; i++) {
                if ($i == "numbering") num = $(i + 1)
                if ($i == "assembly") asm = $(i + 1)
                if ($i == "factorization") fac = $(i + 1)
                if ($i == "solve") sol = $(i + 1)
                if ($i == "fields") fld = $(i + 1)
                if ($i == "total") ms = $(i + 1)
            }
        }
        /checks: / { checks = $2 "_OK_" $4 "_NOOK" }
        /DIAGNOSTIC JOB/ { diag = $NF }
        END {
            printf "ndofs=%s mesh=%s numbering=%s assembly=%s factorization=%s solve=%s fields=%s calc_champ=%s meca=%s checks=%s diag=%s",
                nd, mesh, num, asm, fac, sol, fld, calc, ms, checks, diag
        }' "$mess" 2>/dev/null || true)
    echo "ASTER case=$name cells=$n gen=$tgen load=$load rc=$rc $phases $(time_fields "$dir/aster.time")" | tee -a "$RESULTS" >&2
    # GetFEM, same problem, mesh built in GetFEM.
    local grc=0
    load=$(cut -d' ' -f1 /proc/loadavg)
    OPENBLAS_NUM_THREADS=$GF_THREADS OMP_NUM_THREADS=$GF_THREADS \
        /usr/bin/time -v -o "$dir/getfem.time" "$PY" "$ROOT/scripts/bench_statics_getfem.py" "$gcase" ${n//,/ } \
        >"$dir/getfem.out" 2>"$dir/getfem.err" || grc=$?
    echo "$(grep '^GETFEM' "$dir/getfem.out" || echo "GETFEM case=$gcase failed") name=$name load=$load rc=$grc $(time_fields "$dir/getfem.time")" \
        | tee -a "$RESULTS" >&2
}

run_case quad8_2d QUAD8 "$N2D" 2,1 2d
if [ "$N3D" != none ]; then
    run_case hexa20_3d HEXA20 "$N3D" 3,2,1 3d
fi

# The table.
"$PY" - "$RESULTS" "$GF_THREADS" <<'EOF'
import sys

rows = [dict(kv.split("=", 1) for kv in line.split()[1:] if "=" in kv) for line in open(sys.argv[1])]
aster = [r for r in rows if "cells" in r]
gf = {r.get("name"): r for r in rows if "name" in r}
f = lambda r, k: float(r.get(k) or "nan")
failed = False
print()
print("aster-rs (release, both cores); phases in seconds; mesh = LIRE_MAILLAGE, post = SIEF_ELGA in MECA_STATIQUE"
      " + CALC_CHAMP SIGM_NOEU, other = wall - phases (startup, models, loads, TEST_RESU)")
print("| case | cells | dofs | mesh | numbering | assembly | factorization | solve | post | other | wall | peak RSS MiB"
      " | (total - fact.)/fact. | check |")
print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|")
for r in aster:
    phases = ["mesh", "numbering", "assembly", "factorization", "solve"]
    post = f(r, "fields") + f(r, "calc_champ")
    wall = f(r, "wall")
    other = wall - sum(f(r, k) for k in phases) - post
    fac = f(r, "factorization")
    ok = r.get("rc") == "0" and r.get("diag") == "OK"
    failed |= not ok
    print("| %s | %s | %s | %s | %.2f | %.2f | %.2f | %.0f | %.2f | %s |" % (
        r["case"], r["cells"].replace(",", "×"), r.get("ndofs", "?"),
        " | ".join("%.2f" % f(r, k) for k in phases), post, other, wall, f(r, "rss"),
        (wall - fac) / fac if fac > 0 else float("nan"),
        "%s (%s)" % (r.get("diag"), (r.get("checks") or "").replace("_", " ")) if ok else "FAILED rc=%s" % r.get("rc")))
print()
print("GetFEM 5.4 (python3-getfem, FEM_Q2_INCOMPLETE, Dirichlet with multipliers, MUMPS, OpenBLAS threads: %s);"
      " total = mesh + setup + assembly + solve + check" % sys.argv[2])
print("| case | dofs (u / with multipliers) | mesh | setup | assembly | solve (MUMPS) | total | wall | peak RSS MiB"
      " | check | aster-rs wall / GetFEM wall | aster-rs wall / GetFEM total |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|")
for r in aster:
    g = gf.get(r["case"], {})
    ok = g.get("rc") == "0" and g.get("ok") == "yes"
    failed |= not ok
    print("| %s | %s / %s | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.0f | %s | %.2f | %.2f |" % (
        r["case"], g.get("ndofs_u", "?"), g.get("ndofs", "?"), f(g, "mesh"), f(g, "setup"), f(g, "assembly"),
        f(g, "solve"), f(g, "total"), f(g, "wall"), f(g, "rss"),
        "OK (rel. err. %s)" % g.get("relerr") if ok else "FAILED rc=%s" % g.get("rc"),
        f(r, "wall") / f(g, "wall"), f(r, "wall") / f(g, "total")))
print()
print("mesh generation (aster mesh box, not in the table): " + ", ".join(
    "%s %s s" % (r["case"], r.get("gen")) for r in aster))
print("1-min load average at the start of each run (2 cores; other jobs share the machine): " + ", ".join(
    "%s aster-rs %s / GetFEM %s" % (r["case"], r.get("load"), gf.get(r["case"], {}).get("load")) for r in aster))
sys.exit(1 if failed else 0)
EOF
