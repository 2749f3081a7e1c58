#!/bin/sh
# bench_snake.sh — the full snake scenes of issue 9 (Zhang et al. 2019,
# Suppl. Figs. 10-12): snake_continuum for 10 s; snake_hardening with shear,
# twist, and both hardened 25 times against the original; snake_terrain for
# 30 s, original and hardened 100 times.  Then the same snake under two
# modelling choices of the reference's code (docs/validation.md, "Snakes"):
# its rotational dissipation (rotational_damping = 5 N s/rad, variant R),
# and that with friction at the contact point (variant RC): original and
# x25 for 20 s on flat ground, original and x100 for 30 s on the barrier.
# scripts/snake_report.py compares them, draws docs/img/snake_*.png and
# writes the section "Snakes (issue 9)" of docs/benchmarks.md (replacing an
# older one).
set -e
OUT=build/bench/snake
mkdir -p $OUT
export SINEW_PATH=models
./bin/sinewc examples/snake_continuum.sinew -o $OUT/continuum
./bin/sinewc examples/snake_hardening.sinew -o $OUT/hardening
./bin/sinewc examples/snake_terrain.sinew -o $OUT/terrain
run() { # name sim args... -> runs, appends "name seconds" to the wall-time list
  name=$1; sim=$2; shift 2
  s=$(date +%s.%N)
  $sim --quiet --out $OUT/$name.h5 "$@"
  e=$(date +%s.%N)
  echo "$name $(echo "$e - $s" | bc)" >> $OUT/wall.txt
}
: > $OUT/wall.txt
run continuum $OUT/continuum
run original $OUT/hardening --set shear=1 --set twist=1
run shear25 $OUT/hardening --set twist=1
run twist25 $OUT/hardening --set shear=1
run both25 $OUT/hardening
run terrain_original $OUT/terrain --set hardening=1
run terrain_hardened $OUT/terrain
# the variants: the model with the reference's rotational dissipation, the
# scenes with friction at the contact point
mkdir -p $OUT/models_R
sed 's|^\(    damping = 5 kg/m/s;\)$|\1 rotational_damping = 5 N s/rad;|' \
  models/continuum_snake.sinew > $OUT/models_R/continuum_snake.sinew
grep -q 'rotational_damping = 5 N s/rad' $OUT/models_R/continuum_snake.sinew
for scene in hardening terrain; do
  sed 's|^\(  mu_kinetic = .*;\)$|\1 contact_point = true;|' examples/snake_$scene.sinew \
    > $OUT/snake_${scene}_cp.sinew
  grep -q 'contact_point = true' $OUT/snake_${scene}_cp.sinew
done
SINEW_PATH=$OUT/models_R ./bin/sinewc examples/snake_hardening.sinew -o $OUT/hardening_R
SINEW_PATH=$OUT/models_R ./bin/sinewc $OUT/snake_hardening_cp.sinew -o $OUT/hardening_RC
SINEW_PATH=$OUT/models_R ./bin/sinewc $OUT/snake_terrain_cp.sinew -o $OUT/terrain_RC
for v in R RC; do
  run ${v}_original $OUT/hardening_$v --duration 20s --set shear=1 --set twist=1
  run ${v}_both25 $OUT/hardening_$v --duration 20s
done
run RC_terrain_original $OUT/terrain_RC --set hardening=1
run RC_terrain_hardened $OUT/terrain_RC
/usr/bin/python3 scripts/snake_report.py $OUT docs/benchmarks.md docs/img
