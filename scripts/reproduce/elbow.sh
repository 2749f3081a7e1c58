#!/bin/sh
# elbow.sh — `make reproduce` module: the human elbow's validations of Zhang
# et al. 2019, Suppl. Notes 2.1 and 2.2 (Main Fig. 1c, 1d; Suppl. eqs. 3-5),
# and its flexion against the 50 ns reference curve.
#
# Design.  Force-length (Note 2.1): one biceps head with its tendons
# (examples/elbow_isometric.sinew), fully active, under a dead load F_set =
# F_qs(eta*) from rest length (eta > 1: first stretched by an extra pull that
# fades, the reference's protocol), run until it settles; and, for the
# descending limb where a dead load has no stable equilibrium, the same head
# taken to a length over 0.2 s and held there (the isometric experiment
# itself: a sed copy of the scene with a `velocity` on the distal end).
# Force-velocity (Note 2.2): the whole arm (examples/elbow_isokinetic.sinew),
# both heads fully active, the forearm turned at omega; the force as the
# stretch passes 0.85 against F_qs - zeta(v) v / l0 (Suppl. eq. 5).  Flexion:
# examples/elbow_flexion.sinew against examples/reference/elbow_flexion_50ns.csv
# (position Verlet at 50 ns), and with the bones rigid (the reference's
# arm; sinew's are elastic).
# The flexion is compared over the whole 0.5 s (the scene moves the arm's
# 150 deg stop out of the way: the reference's arm flexes to 153.6 deg).
# quick: the single head's tendons implicit under imex at 50 us (a sed copy;
#   within 1e-6 of the stretch of the explicit tendons), 10 s under a load
#   (the point near the peak settles slowly), 1 s held; isokinetic at 80,
#   160 and 240 deg/s at the scene's explicit step, each run until 20 ms
#   after eta = 0.85; the flexion in make demo's configuration (imex, bones
#   and tendons implicit, 125 us).
# full: the scenes as written (position Verlet at half the stable estimate),
#   the load-controlled points run 15 s; isokinetic at six rates, 40 to 240
#   deg/s; the flexion at the scene's explicit step.
#   scripts/reproduce/elbow.sh quick|full OUTDIR
set -eu
BUDGET=$1 OUT=$2
case $BUDGET in quick|full) ;; *) echo "budget: quick or full" >&2; exit 2 ;; esac
export SINEW_PATH=models
rm -f "$OUT/failed"

# the scenes: the isometric head with implicit tendons (quick) and held
sed 's|^\(  elements = 7;\)$|\1 implicit = implicit_tendons;|' examples/elbow_isometric.sinew |
  sed 's|^\(simulate .*\)$|let implicit_tendons = false;\n\1|' > "$OUT/elbow_isometric_lets.sinew"
[ "$(grep -c 'implicit = implicit_tendons' "$OUT/elbow_isometric_lets.sinew")" = 2 ]
sed '/^force distal.end/d; /^param pre/d' "$OUT/elbow_isometric_lets.sinew" |
  sed 's|^param F_set = .*$|param travel = 0 m;                  # the distal end moved over 0.2 s, then held|' \
  > "$OUT/elbow_held.sinew"
cat >> "$OUT/elbow_held.sinew" <<'EOF'
velocity distal.end = (0, 0, -1) * travel * 10 / s * table(times = (0, 0.1, 0.2) s, values = (0, 1, 0));
EOF
grep -q '^param travel' "$OUT/elbow_held.sinew"
if [ "$BUDGET" = quick ]; then
  LETS="--let implicit_tendons=true" ISO="--integrator imex --dt 50us"
  TLOAD=10s THELD=1s OMEGAS="80 160 240"
  FLEX_LETS="--let implicit_bones=true --let implicit_tendons=true" FLEX="--integrator imex --dt 125us"
  RIGID="--integrator imex"
else
  LETS="" ISO="" TLOAD=15s THELD=1s OMEGAS="40 80 120 160 200 240"
  FLEX_LETS="" FLEX="" RIGID=""
fi
./bin/sinewc "$OUT/elbow_isometric_lets.sinew" $LETS -o "$OUT/isometric"
./bin/sinewc "$OUT/elbow_held.sinew" $LETS -o "$OUT/held"
./bin/sinewc examples/elbow_isokinetic.sinew -o "$OUT/isokinetic"
./bin/sinewc examples/elbow_flexion.sinew $FLEX_LETS -o "$OUT/flexion"
./bin/sinewc examples/elbow_flexion.sinew --let rigid_bones=true -o "$OUT/flexion_rigid"

run() { # run NAME SIM ARGS...: one simulation, its log beside it
  name=$1 sim=$2; shift 2
  "$sim" --quiet --out "$OUT/$name.h5" "$@" > "$OUT/$name.log" 2>&1 ||
    { echo "elbow.sh: $name failed:"; tail -3 "$OUT/$name.log"; touch "$OUT/failed"; }
}
# two at a time, on two cores: queue JOB... (each a quoted run line)
pids=""
queue() {
  eval "run $*" & pids="$pids $!"
  set -- $pids
  if [ $# -ge 2 ]; then wait "$1" || true; shift; pids="$*"; fi
}
drain() { for p in $pids; do wait "$p" || true; done; pids=""; }

# the points: eta* and F_set = F_qs(eta*) F_max of one head (the report's formulas)
PLAN=$(/usr/bin/python3 scripts/reproduce/elbow_report.py plan)
echo "$PLAN" | while read -r kind name value pre; do
  case $kind in
    load) echo "queue $name $OUT/isometric $ISO --duration $TLOAD --set F_set=$value --set pre=$pre" ;;
    held) echo "queue $name $OUT/held $ISO --duration $THELD --set travel=$value" ;;
  esac
done > "$OUT/plan.sh"
for w in $OMEGAS; do  # the stretch passes 0.85 about 39 deg after the turn starts at 0.1 s
  T=$(awk "BEGIN { printf \"%.3f\", 0.1 + 45 / $w + 0.02 }")
  echo "queue isokinetic_$w $OUT/isokinetic --duration ${T}s --set omega=${w}deg/s" >> "$OUT/plan.sh"
done
echo "queue flexion $OUT/flexion $FLEX" >> "$OUT/plan.sh"
echo "queue flexion_rigid $OUT/flexion_rigid $RIGID" >> "$OUT/plan.sh"
. "$OUT/plan.sh"
drain
[ ! -e "$OUT/failed" ] || exit 1
/usr/bin/python3 scripts/reproduce/elbow_report.py report "$OUT" "$BUDGET" "$OMEGAS"
