#!/usr/bin/env bash
# Benchmark of 3D transient heat conduction (issue 25, acceptance point 4): THER_LINEAIRE on a HEXA8 box
# of about 1 M temperatures, a few θ-scheme steps; the wall time of every command, the solver's phases and
# the peak memory.
#
#   scripts/bench_heat.sh                  # 100 x 100 x 100 HEXA8 (1,030,301 temperatures), 4 steps
#   BENCH_N=20,20,20 scripts/bench_heat.sh # quick smoke run
#
# Environment:
#   BENCH_N=NX,NY,NZ   HEXA8 cells of the 1 x 1 x 1 box (default 100,100,100)
#   BENCH_STEPS=K      θ-scheme steps at a constant Δt (default 4: one factorization, then solves)
#   BENCH_DIR=PATH     work folder (default: a fresh temp folder, removed at the end)
#
# The scene: T = 100 held on XMIN from t = 0+, an exchange h (T_ext − T) on XMAX, the rest insulated, from
# T = 0 (ETAT_INIT VALE), λ = 1, ρCp = 1, Δt = 0.01; one TEST_RESU checks that the temperature stays
# within [0, 100]. The run goes under `/usr/bin/time -v` (wall time, peak RSS); the phases are read
# from the .mess file.
set -euo pipefail

ROOT=$(cd "$(dirname "$0")/.." && pwd)
cd "$ROOT"
N=${BENCH_N:-100,100,100}
STEPS=${BENCH_STEPS:-4}
echo "== cargo build --release" >&2
cargo build --release 2>&1 | tail -1 >&2
ASTER="$ROOT/target/release/aster"
if [ -n "${BENCH_DIR:-}" ]; then
    WORK=$BENCH_DIR
    mkdir -p "$WORK"
else
    WORK=$(mktemp -d /tmp/bench_heat.XXXXXX)
    trap 'rm -rf "$WORK"' EXIT
fi
"$ASTER" mesh box --cell HEXA8 --n "$N" --size 1,1,1 -o "$WORK/box.med" >/dev/null
cat >"$WORK/heat.comm" <<COMM
DEBUT(CODE="OUI")
MA = LIRE_MAILLAGE(FORMAT="MED", UNITE=20)
MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT="OUI", PHENOMENE="THERMIQUE", MODELISATION="3D"))
MAT = DEFI_MATERIAU(THER=_F(LAMBDA=1.0, RHO_CP=1.0))
CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT="OUI", MATER=MAT))
CH = AFFE_CHAR_THER(MODELE=MO, TEMP_IMPO=_F(GROUP_NO="XMIN", TEMP=100.0),
                    ECHANGE=_F(GROUP_MA="XMAX", COEF_H=10.0, TEMP_EXT=20.0))
LI = DEFI_LIST_REEL(DEBUT=0.0, INTERVALLE=_F(JUSQU_A=0.01 * $STEPS, NOMBRE=$STEPS))
RES = THER_LINEAIRE(MODELE=MO, CHAM_MATER=CM, EXCIT=_F(CHARGE=CH), INCREMENT=_F(LIST_INST=LI),
                    ETAT_INIT=_F(VALE=0.0), ARCHIVAGE=_F(PAS_ARCH=$STEPS))
TEST_RESU(RESU=_F(RESULTAT=RES, INST=0.01 * $STEPS, NOM_CHAM="TEMP", NOM_CMP="TEMP", TYPE_TEST="MAX",
                  VALE_CALC=100.0, VALE_REFE=100.0, PRECISION=1e-6, REFERENCE="ANALYTIQUE"))
FIN()
COMM
/usr/bin/time -v "$ASTER" run "$WORK/heat.comm" --unit 20="$WORK/box.med" --out "$WORK/out" -q \
    >"$WORK/stdout.txt" 2>"$WORK/time.txt" || { cat "$WORK/stdout.txt" "$WORK/time.txt" >&2; exit 1; }
wall=$(awk -F': ' '/Elapsed \(wall clock\)/ { n = split($2, t, ":"); s = 0; for (i = 1; i <= n; i++) s = s * 60 + t[i]; print s }' "$WORK/time.txt")
rss=$(awk -F': ' '/Maximum resident set size/ { printf "%.0f", $2 / 1024 }' "$WORK/time.txt")
echo "box $N HEXA8, $STEPS steps: wall ${wall} s, peak ${rss} MiB"
grep -E "heat conduction|time:|solver|# End of command" "$WORK/out/heat.mess" | sed 's/^/  /'
