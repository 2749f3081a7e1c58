#!/bin/sh
# snake_terrain.sh — `make reproduce` module: the continuum snake on the
# barrier of Zhang et al. 2019, Suppl. Note 6.6, Figs. 11-12 (the original
# and the snake hardened x100 in shear and twist), against the reference's
# own code run as an oracle (bench/oracle/snake_oracle_results.json).
# quick and full: the scene's 30 s, both snakes; full also under the
# reference code's conventions (rotational_damping = 5 N s/rad,
# contact_point = true; sed, as bench/bench_snake.sh does).
#   scripts/reproduce/snake_terrain.sh quick|full OUTDIR
set -eu
BUDGET=$1 OUT=$2
case $BUDGET in quick|full) ;; *) echo "budget: quick or full" >&2; exit 2 ;; esac
export SINEW_PATH=models
./bin/sinewc examples/snake_terrain.sinew -o "$OUT/terrain"
run() { # run NAME SIM ARGS...
  name=$1 sim=$2; shift 2
  "$sim" --quiet --out "$OUT/$name.h5" "$@" > "$OUT/$name.log" 2>&1 ||
    { echo "snake_terrain.sh: $name failed:"; tail -3 "$OUT/$name.log"; return 1; }
}
run original "$OUT/terrain" --set hardening=1 & a=$!
run hardened "$OUT/terrain" & b=$!
wait $a; wait $b
if [ "$BUDGET" = full ]; then
  mkdir -p "$OUT/models_RC"
  sed 's|^\(    damping = 5 kg/m/s;\)$|\1 rotational_damping = 5 N s/rad;|' \
    models/continuum_snake.sinew > "$OUT/models_RC/continuum_snake.sinew"
  sed 's|^\(  mu_kinetic = .*;\)$|\1 contact_point = true;|' examples/snake_terrain.sinew \
    > "$OUT/snake_terrain_RC.sinew"
  grep -q 'rotational_damping = 5 N s/rad' "$OUT/models_RC/continuum_snake.sinew"
  grep -q 'contact_point = true' "$OUT/snake_terrain_RC.sinew"
  SINEW_PATH="$OUT/models_RC" ./bin/sinewc "$OUT/snake_terrain_RC.sinew" -o "$OUT/terrain_RC"
  run RC_original "$OUT/terrain_RC" --set hardening=1 & a=$!
  run RC_hardened "$OUT/terrain_RC" & b=$!
  wait $a; wait $b
fi
/usr/bin/python3 scripts/reproduce/snake_terrain_report.py "$OUT" "$BUDGET"
