#!/bin/sh
# snake_continuum.sh — `make reproduce` module: the continuum snake on flat
# ground and its twist and shear hardening (Zhang et al. 2019, Suppl. Note
# 6.5, Fig. 10), against the reference's own code run as an oracle
# (PyElastica, docs/validation.md, "The reference's own code on the same
# claims").  Runs examples/snake_hardening.sinew original, x25 shear and
# twist, shear only and twist only, under sinew's defaults; and the original
# under the reference code's two conventions (its rotational dissipation,
# rotational_damping = 5 N s/rad, and friction at the contact point,
# contact_point = true: the model and scene rewritten by sed, as
# bench/bench_snake.sh does); and the original under the reference's
# rotational dissipation with friction on the centreline (R), where the
# muscle moment's axis does not matter (docs/validation.md, "Why the sway
# differs").  quick: 5 s each (the oracle's clean window is 2-5 s); full:
# the reference's 10 s, and the x25 snake under the reference code's
# conventions too.
#   scripts/reproduce/snake_continuum.sh quick|full OUTDIR
set -eu
BUDGET=$1 OUT=$2
case $BUDGET in quick) T=5s ;; full) T=10s ;; *) echo "budget: quick or full" >&2; exit 2 ;; esac
export SINEW_PATH=models
./bin/sinewc examples/snake_hardening.sinew -o "$OUT/hardening"
mkdir -p "$OUT/models_RC"
sed 's|^\(    damping = 5 kg/m/s;\)$|\1 rotational_damping = 5 N s/rad;|' \
  models/continuum_snake.sinew > "$OUT/models_RC/continuum_snake.sinew"
grep -q 'rotational_damping = 5 N s/rad' "$OUT/models_RC/continuum_snake.sinew"
sed 's|^\(  mu_kinetic = .*;\)$|\1 contact_point = true;|' examples/snake_hardening.sinew \
  > "$OUT/snake_hardening_RC.sinew"
grep -q 'contact_point = true' "$OUT/snake_hardening_RC.sinew"
SINEW_PATH="$OUT/models_RC" ./bin/sinewc "$OUT/snake_hardening_RC.sinew" -o "$OUT/hardening_RC"
SINEW_PATH="$OUT/models_RC" ./bin/sinewc examples/snake_hardening.sinew -o "$OUT/hardening_R"
run() { # run NAME SIM ARGS...
  name=$1 sim=$2; shift 2
  "$sim" --quiet --duration $T --out "$OUT/$name.h5" "$@" > "$OUT/$name.log" 2>&1 ||
    { echo "snake_continuum.sh: $name failed:"; tail -3 "$OUT/$name.log"; return 1; }
}
# two at a time, on two cores
run original "$OUT/hardening" --set shear=1 --set twist=1 & a=$!
run both25 "$OUT/hardening" & b=$!
wait $a; wait $b
run shear25 "$OUT/hardening" --set twist=1 & a=$!
run twist25 "$OUT/hardening" --set shear=1 & b=$!
wait $a; wait $b
run RC_original "$OUT/hardening_RC" --set shear=1 --set twist=1 & a=$!
run R_original "$OUT/hardening_R" --set shear=1 --set twist=1 & b=$!
wait $a; wait $b
if [ "$BUDGET" = full ]; then run RC_both25 "$OUT/hardening_RC"; fi
/usr/bin/python3 scripts/reproduce/snake_continuum_report.py "$OUT" "$BUDGET" "$T"
