#!/bin/sh
# elbow_hardening.sh — `make reproduce` module: the elbow flexion with the
# muscles' twist and shear hardened 10^4 times and the tendons' 10 times
# (Zhang et al. 2019, Suppl. Note 6.1, Fig. 6): twist only, shear only and
# both against the original; the reference's claim is that none changes the
# joint angle, and that no spurious oscillation arises.
#
# Design.  examples/elbow_hardening.sinew at its explicit step (position
# Verlet at half the stable estimate, the scene's integrator: the claim is
# about the scheme's behaviour under stiff shear and twist, so no mode is
# made implicit), the four cases as --set choices of one simulator; the
# original again at dt/2, which measures the step's own error; and the
# original under the reference code's shear modulus G = E / (1 + nu) = 2E/3
# (Fig. 6's caption; sinew's default is E / (2 (1 + nu))) for muscles,
# tendons and bones, a sed copy of models/human_arm.sinew.
# quick and full: the reference's 0.5 s (Suppl. Table 5) at the scene's
# step; full adds the original and the doubly hardened arm at the
# reference's dt = 50 ns.
#   scripts/reproduce/elbow_hardening.sh quick|full OUTDIR
set -eu
BUDGET=$1 OUT=$2
case $BUDGET in quick|full) ;; *) echo "budget: quick or full" >&2; exit 2 ;; esac
export SINEW_PATH=models
./bin/sinewc examples/elbow_hardening.sinew -o "$OUT/hardening"
mkdir -p "$OUT/models_G"
sed -e 's|^\(material bone_tissue   { E = 15 GPa; \)|\1 G = 10 GPa;|' \
    -e 's|^\(material tendon_tissue { E = 500 MPa; \)|\1G = 333.3333 MPa; |' \
    -e 's|^\(material muscle_tissue { E = 10 kPa; \)|\1 G = 6.666667 kPa;|' \
    models/human_arm.sinew > "$OUT/models_G/human_arm.sinew"
[ "$(grep -c '^material .* G = ' "$OUT/models_G/human_arm.sinew")" = 3 ]
SINEW_PATH="$OUT/models_G" ./bin/sinewc examples/elbow_hardening.sinew -o "$OUT/hardening_G"
run() { # run NAME SIM ARGS...
  name=$1 sim=$2; shift 2
  "$sim" --quiet --out "$OUT/$name.h5" "$@" > "$OUT/$name.log" 2>&1 ||
    { echo "elbow_hardening.sh: $name failed:"; tail -3 "$OUT/$name.log"; return 1; }
}
ORIG="--set muscle_shear=1 --set muscle_twist=1 --set tendon_shear=1 --set tendon_twist=1"
# two at a time, on two cores
run original "$OUT/hardening" $ORIG & a=$!
run both "$OUT/hardening" & b=$!
wait $a; wait $b
DT=$(/usr/bin/python3 -c "import h5py; print(h5py.File('$OUT/original.h5', 'r').attrs['dt'])")
DT2=$(awk "BEGIN { printf \"%.10gs\", $DT / 2 }")
run twist "$OUT/hardening" --set muscle_shear=1 --set tendon_shear=1 & a=$!
run shear "$OUT/hardening" --set muscle_twist=1 --set tendon_twist=1 & b=$!
wait $a; wait $b
run original_dt2 "$OUT/hardening" $ORIG --dt "$DT2" & a=$!
run original_G "$OUT/hardening_G" $ORIG --dt "${DT}s" & b=$!
wait $a; wait $b
if [ "$BUDGET" = full ]; then
  run original_50ns "$OUT/hardening" $ORIG --dt 50ns & a=$!
  run both_50ns "$OUT/hardening" --dt 50ns & b=$!
  wait $a; wait $b
fi
/usr/bin/python3 scripts/reproduce/elbow_hardening_report.py "$OUT" "$BUDGET" "$DT"
