#!/bin/sh
# bench_snake.sh — the full snake scenes of issue 9 (Zhang et al. 2019,
# Suppl. Figs. 10-12): snake_continuum for 10 s; snake_hardening with shear,
# twist, and both hardened 25 times against the original; snake_terrain for
# 30 s, original and hardened 100 times.  scripts/snake_report.py compares
# them, draws docs/img/snake_*.png and writes the section "Snakes (issue 9)"
# of docs/benchmarks.md (replacing an older one).
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
/usr/bin/python3 scripts/snake_report.py $OUT docs/benchmarks.md docs/img
