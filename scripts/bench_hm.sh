#!/usr/bin/env bash
# Benchmarks of the hydro-mechanics (issue 11, acceptance 6 and 3b), in one run:
#  (a) the consolidation of a saturated block under a load on its drained top, coupled HM solved by our
#      STAT_NON_LINE driver: 2D (D_PLAN_HM, QUAD8, BENCH_HM_2D = NX,NY cells) and 3D (3D_HM, HEXA20,
#      BENCH_HM_3D = NX,NY,NZ), BENCH_HM_STEPS time steps: wall time, peak memory, time per command and
#      the HM driver's own split (elements and assembly, analysis, factorization, condition estimate,
#      solves), Newton iterations per step. The liquid is incompressible (BENCH_HM_UNSURK = UN_SUR_K,
#      default 0): the tangent is then symmetric once its pressure rows are scaled, and LDLᵀ solves it;
#      a compressible liquid (e.g. BENCH_HM_UNSURK=5e-10) makes it non-symmetric, solved by LU;
#  (b) the WTNV149 junction scene comm/junction_2d.comm (D_PLAN) against comm/junction_2d_hm.comm
#      (D_PLAN_HM, every hydraulic unknown prescribed to zero and eliminated) on the same N x N mesh
#      (BENCH_HM_N), one after the other, BENCH_HM_REPEAT times each (fastest kept): the ratio of walls.
#
#  (c) a fluid-filled junction (issue 14, acceptance 4): the block of the junction scene crossed by its
#      two interfaces meeting at the junction, in D_PLAN_HM with coupled flow in the X-FEM elements
#      (Heaviside-enriched displacement and pressure, impervious and traction-free interfaces), loaded on
#      its drained top, drained at the bottom, sides held: the wedge between the interfaces stays
#      undrained. BENCH_HM_JF = N (N x N QUAD8 cells; 180 gives ~305 k unknowns), 3 steps after a ramp:
#      wall time by command and the HM driver's split.
#
#   scripts/bench_hm.sh                                     # the issue's sizes
#   BENCH_HM_2D=40,40 BENCH_HM_3D=6,6,6 BENCH_HM_N=32 scripts/bench_hm.sh   # quick smoke run
#   BENCH_HM_3D=none scripts/bench_hm.sh                    # skip a case
#   BENCH_HM_2D=none BENCH_HM_3D=none BENCH_HM_N=16 BENCH_HM_REPEAT=1 scripts/bench_hm.sh   # (c) alone, in effect
#
# Wall time and peak memory come from /usr/bin/time -v; the rest from the .mess. Reports, never asserts.
set -euo pipefail

ROOT=$(cd "$(dirname "$0")/.." && pwd)
cd "$ROOT"
S2=${BENCH_HM_2D:-267,267}
S3=${BENCH_HM_3D:-24,24,24}
NJ=${BENCH_HM_N:-320}
NF=${BENCH_HM_JF:-180}
STEPS=${BENCH_HM_STEPS:-3}
UNSURK=${BENCH_HM_UNSURK:-0.0}
REPEAT=${BENCH_HM_REPEAT:-3}
cargo build --release -q
ASTER=$ROOT/target/release/aster
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT

. "$ROOT/scripts/bench_lib.sh"

# The consolidation scene: MODEL, the side conditions and the load skin are filled in per dimension.
consolidation() {
    cat <<EOF
DEBUT(CODE="OUI")
MA = LIRE_MAILLAGE(FORMAT="MED", UNITE=20)
MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="$1"))
UN = DEFI_CONSTANTE(VALE=1.0)
ZERO = DEFI_CONSTANTE(VALE=0.0)
KINT = DEFI_CONSTANTE(VALE=1.0e-8)
SOL = DEFI_MATERIAU(
    ELAS=_F(E=1.0e7, NU=0.3),
    COMP_THM="LIQU_SATU",
    THM_INIT=_F(PRE1=0.0, PORO=0.3),
    THM_DIFFU=_F(RHO=2000.0, BIOT_COEF=1.0, PESA_X=0.0, PESA_Y=0.0, PESA_Z=0.0, PERM_IN=KINT),
    THM_LIQU=_F(RHO=1000.0, UN_SUR_K=$UNSURK, VISC=UN, D_VISC_TEMP=ZERO),
)
CHMAT = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT="OUI", MATER=SOL))
CHAR = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=($2), PRES_REP=_F(GROUP_MA="$3", PRES=1.0e4))
L = DEFI_LIST_REEL(DEBUT=0.0, INTERVALLE=(_F(JUSQU_A=1.0e-4, NOMBRE=1), _F(JUSQU_A=100.0, NOMBRE=$STEPS)))
RES = STAT_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=CHAR), SCHEMA_THM=_F(PARM_THETA=1.0),
                    COMPORTEMENT=_F(RELATION="KIT_HM", RELATION_KIT=("ELAS", "LIQU_SATU", "HYDR_UTIL")),
                    INCREMENT=_F(LIST_INST=L))
FIN()
EOF
}

echo "## Coupled consolidation ($STEPS steps after the undrained one, UN_SUR_K = $UNSURK; load $(load) at start)"
echo
echo "| case | cells | unknowns | solved | wall (s) | peak (GiB) | LIRE_MAILLAGE | AFFE_* + DEFI_* | STAT_NON_LINE | elements + assembly | analysis | factorization | condition (1st) | solves | factorizations | Newton / step | factor | load |"
echo "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|"
run_consolidation() { # name size cell model ddl skin
    local d=$WORK/$1 n=$2
    [ "$n" = none ] && return
    mkdir -p "$d"
    "$ASTER" mesh box --cell "$3" --n "$n" --size "$(echo "$n" | sed 's/[0-9]*/1/g')" -o "$d/m.med" >/dev/null
    consolidation "$4" "$5" "$6" >"$d/c.comm"
    local l
    l=$(load)
    /usr/bin/time -v -o "$d/time" "$ASTER" run "$d/c.comm" --unit 20="$d/m.med" --out "$d" -q >/dev/null 2>&1 || true
    local mess=$d/c.mess
    local unk solved tline steps iters setup fact
    unk=$(grep -m1 "unknowns  :" "$mess" | sed 's/.*unknowns  : \([0-9]*\) .*/\1/')
    solved=$(grep -m1 "unknowns  :" "$mess" | sed 's/.*, \([0-9]*\) solved.*/\1/')
    tline=$(grep -m1 "    time      :" "$mess")
    steps=$(grep -m1 "    steps     :" "$mess" | sed 's/.*, \([0-9]*\) computed.*/\1/')
    iters=$(grep -m1 "    steps     :" "$mess" | sed 's/.*, \([0-9]*\) Newton iterations.*/\1/')
    fact=$(grep -m1 -A1 "    solver    :" "$mess" | tail -1 | sed 's/^ *//; s/, condition estimate.*//')
    setup=$(awk '/# End of command #[0-9]+ (AFFE_|DEFI_)/ { s += $(NF - 1) } END { printf "%.2f", s }' "$mess")
    f() { echo "$tline" | sed "s/.*$1 \([0-9.]*\) s.*/\1/"; }
    echo "| $1 $(grep -m1 'DIAGNOSTIC JOB' "$mess" | awk '{print $NF}') | $n | $unk | $solved | $(wall "$d/time") | $(rss "$d/time") | $(cmd_time "$mess" LIRE_MAILLAGE) | $setup | $(cmd_time "$mess" STAT_NON_LINE) | $(f 'elements and assembly') | $(f 'analysis') | $(f ', factorization') | $(f 'condition (first factorization)') | $(f 'solves') | $(echo "$tline" | sed 's/.*; \([0-9]*\) factorizations.*/\1/') | $(awk -v i="$iters" -v s="$steps" 'BEGIN { printf "%.2f", i / s }') | $fact | $l |"
}
run_consolidation 2D "$S2" QUAD8 D_PLAN_HM \
    '_F(GROUP_NO="HAUT", PRE1=0.0), _F(GROUP_NO="BAS", DX=0.0, DY=0.0), _F(GROUP_NO=("GAUCHE", "DROITE"), DX=0.0)' HAUT
run_consolidation 3D "$S3" HEXA20 3D_HM \
    '_F(GROUP_NO="YMAX", PRE1=0.0), _F(GROUP_NO="YMIN", DX=0.0, DY=0.0, DZ=0.0), _F(GROUP_NO=("XMIN", "XMAX"), DX=0.0), _F(GROUP_NO=("ZMIN", "ZMAX"), DZ=0.0)' YMAX

echo
echo "## Junction scene: D_PLAN against D_PLAN_HM with the hydraulics eliminated (N = $NJ, best of $REPEAT)"
echo
echo "| scene | solved | wall (s) | peak (GiB) | DEFI_FISS_XFEM | MODI_MODELE_XFEM | STAT_NON_LINE | POST_* | checks | load |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|---|---:|"
d=$WORK/junction
mkdir -p "$d"
"$ASTER" mesh box --cell QUAD8 --n "$NJ,$NJ" --size 10,10 -o "$d/m.med" >/dev/null
declare -A best row
for k in $(seq "$REPEAT"); do
    # Alternate the order so that neither scene always runs on a warmer machine.
    if [ $((k % 2)) = 1 ]; then order="junction_2d junction_2d_hm"; else order="junction_2d_hm junction_2d"; fi
    for s in $order; do
        l=$(load)
        /usr/bin/time -v -o "$d/$s.time" "$ASTER" run "comm/$s.comm" --unit 20="$d/m.med" --unit 80="$d/$s.rmed" \
            --out "$d" -q >/dev/null 2>&1 || true
        w=$(wall "$d/$s.time")
        if [ -z "${best[$s]:-}" ] || awk -v a="$w" -v b="${best[$s]}" 'BEGIN { exit !(a < b) }'; then
            best[$s]=$w
            mess=$d/$s.mess
            row[$s]="| $s | $(grep -m1 "unknowns  :" "$mess" | sed 's/.*, \([0-9]*\) solved.*/\1/') | $w | $(rss "$d/$s.time") | $(cmd_time "$mess" DEFI_FISS_XFEM) | $(cmd_time "$mess" MODI_MODELE_XFEM) | $(cmd_time "$mess" STAT_NON_LINE) | $(awk '/# End of command #[0-9]+ POST_/ { s += $(NF - 1) } END { printf "%.2f", s }' "$mess") | $(grep -m1 'checks:' "$mess" | sed 's/^ *//; s/ *elapsed.*//') | $l |"
            grep -m1 "eliminated: hydraulics" "$mess" | sed 's/^ */    /; s/;.*//' >"$d/$s.elim" || true
        fi
    done
done
echo "${row[junction_2d]}"
echo "${row[junction_2d_hm]}"
echo
echo "ratio D_PLAN_HM / D_PLAN (wall, best of $REPEAT): $(awk -v a="${best[junction_2d_hm]}" -v b="${best[junction_2d]}" 'BEGIN { printf "%.3f", a / b }')"
echo "D_PLAN_HM log: $(cat "$d/junction_2d_hm.elim")"

[ "$NF" = none ] && exit 0
echo
echo "## Fluid-filled junction: coupled flow in the X-FEM elements (N = $NF, load $(load) at start)"
echo
echo "| cells | unknowns | solved | wall (s) | peak (GiB) | DEFI_FISS_XFEM | MODI_MODELE_XFEM | STAT_NON_LINE | elements + assembly | analysis | factorization | solves | POST_MAIL_XFEM + POST_CHAM_XFEM | Heaviside sets |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|"
d=$WORK/fluid
mkdir -p "$d"
"$ASTER" mesh box --cell QUAD8 --n "$NF,$NF" --size 10,10 -o "$d/m.med" >/dev/null
cat >"$d/c.comm" <<'EOF'
DEBUT(CODE="OUI")
MA = LIRE_MAILLAGE(FORMAT="MED", UNITE=20)
MO0 = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="D_PLAN_HM"))
LN1 = FORMULE(VALE="Y-0.5*X-2.7", NOM_PARA=["X", "Y"])
LN2 = FORMULE(VALE="Y+0.5*X-7.3", NOM_PARA=["X", "Y"])
FISS1 = DEFI_FISS_XFEM(MAILLAGE=MA, TYPE_DISCONTINUITE="INTERFACE", DEFI_FISS=_F(FONC_LN=LN1))
FISS2 = DEFI_FISS_XFEM(MAILLAGE=MA, TYPE_DISCONTINUITE="INTERFACE", DEFI_FISS=_F(FONC_LN=LN2),
                       JONCTION=_F(FISSURE=FISS1, POINT=(7.0, 0.0)))
MO = MODI_MODELE_XFEM(MODELE_IN=MO0, FISSURE=(FISS1, FISS2))
UN = DEFI_CONSTANTE(VALE=1.0e-3)
ZERO = DEFI_CONSTANTE(VALE=0.0)
KINT = DEFI_CONSTANTE(VALE=1.0e-12)
ROCHE = DEFI_MATERIAU(
    ELAS=_F(E=5.8e9, NU=0.2),
    COMP_THM="LIQU_SATU",
    THM_INIT=_F(PRE1=0.0, PORO=0.1),
    THM_DIFFU=_F(RHO=2500.0, BIOT_COEF=1.0, PESA_X=0.0, PESA_Y=0.0, PESA_Z=0.0, PERM_IN=KINT),
    THM_LIQU=_F(RHO=1000.0, UN_SUR_K=0.0, VISC=UN, D_VISC_TEMP=ZERO),
)
CHMAT = AFFE_MATERIAU(MAILLAGE=MA, MODELE=MO, AFFE=_F(TOUT="OUI", MATER=ROCHE))
CHAR = AFFE_CHAR_MECA(MODELE=MO, PRES_REP=_F(GROUP_MA="HAUT", PRES=1.0e6),
                      DDL_IMPO=(_F(GROUP_MA="BAS", DY=0.0, PRE1=0.0), _F(GROUP_MA="HAUT", PRE1=0.0),
                                _F(GROUP_MA=("GAUCHE", "DROITE"), DX=0.0, DY=0.0)))
RAMPE = DEFI_FONCTION(NOM_PARA="INST", VALE=(0.0, 0.0, 1.0, 1.0), PROL_DROITE="CONSTANT")
L = DEFI_LIST_REEL(DEBUT=0.0, INTERVALLE=(_F(JUSQU_A=1.0, NOMBRE=1), _F(JUSQU_A=1.0e4, NOMBRE=3)))
RES = STAT_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=CHAR, FONC_MULT=RAMPE),
                    SCHEMA_THM=_F(PARM_THETA=1.0),
                    COMPORTEMENT=_F(RELATION="KIT_HM", RELATION_KIT=("ELAS", "LIQU_SATU", "HYDR_UTIL")),
                    INCREMENT=_F(LIST_INST=L))
MAX = POST_MAIL_XFEM(MODELE=MO)
MOV = AFFE_MODELE(MAILLAGE=MAX, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="D_PLAN_HM"))
RESV = POST_CHAM_XFEM(MODELE_VISU=MOV, RESULTAT=RES)
FIN()
EOF
/usr/bin/time -v -o "$d/time" "$ASTER" run "$d/c.comm" --unit 20="$d/m.med" --out "$d" -q >/dev/null 2>&1 || true
mess=$d/c.mess
tline=$(grep -m1 "    time      :" "$mess")
f() { echo "$tline" | sed "s/.*$1 \([0-9.]*\) s.*/\1/"; }
unk=$(grep -m1 "unknowns  :" "$mess" | sed 's/.*unknowns  : \([0-9]*\) .*/\1/')
solved=$(grep -m1 "unknowns  :" "$mess" | sed 's/.*, \([0-9]*\) solved.*/\1/')
sets=$(grep -m1 "X-FEM     :" "$mess" | sed 's/.*X-FEM     : \([0-9]*\) Heaviside sets over \([0-9]*\) nodes.*/\1 over \2 nodes/')
post=$(awk '/# End of command #[0-9]+ POST_(MAIL|CHAM)_XFEM/ { s += $(NF - 1) } END { printf "%.2f", s }' "$mess")
echo "| $NF x $NF | $unk | $solved | $(wall "$d/time") | $(rss "$d/time") | $(cmd_time "$mess" DEFI_FISS_XFEM) | $(cmd_time "$mess" MODI_MODELE_XFEM) | $(cmd_time "$mess" STAT_NON_LINE) | $(f 'elements and assembly') | $(f 'analysis') | $(f ', factorization') | $(f 'solves') | $post | $sets |"
grep -m1 'DIAGNOSTIC JOB' "$mess" | sed 's/^ */run: /'

# The same mesh under comm/fluid_interface_2d.comm: one cohesive interface filled with fluid at a
# prescribed pressure, the exchange with the rock on each side solved (the 2020 interface hydraulics).
l=$(load)
/usr/bin/time -v -o "$d/fi.time" "$ASTER" run comm/fluid_interface_2d.comm --unit 20="$d/m.med" --out "$d" -q \
    >/dev/null 2>&1 || true
mess=$d/fluid_interface_2d.mess
echo
echo "Fluid-filled interface (comm/fluid_interface_2d.comm on the same mesh, load $l at start):"
echo
echo "| unknowns | solved | wall (s) | peak (GiB) | DEFI_FISS_XFEM | MODI_MODELE_XFEM | STAT_NON_LINE | POST_* | checks |"
echo "|---:|---:|---:|---:|---:|---:|---:|---:|---|"
echo "| $(grep -m1 "unknowns  :" "$mess" | sed 's/.*unknowns  : \([0-9]*\).*/\1/') | $(grep -m1 "unknowns  :" "$mess" | sed 's/.*, \([0-9]*\) solved.*/\1/') | $(wall "$d/fi.time") | $(rss "$d/fi.time") | $(cmd_time "$mess" DEFI_FISS_XFEM) | $(cmd_time "$mess" MODI_MODELE_XFEM) | $(cmd_time "$mess" STAT_NON_LINE) | $(awk '/# End of command #[0-9]+ POST_/ { s += $(NF - 1) } END { printf "%.2f", s }' "$mess") | $(grep -m1 'checks:' "$mess" | sed 's/^ *//; s/ *elapsed.*//') |"
