#!/bin/sh
# walker.sh BUDGET OUTDIR — twist and shear hardening of the bio-hybrid
# walker (Zhang et al. 2019, Suppl. Note 6.4, Table 8, Fig. 9): the muscle's
# twist and shear stiffness hardened 10 times, the scaffold's 10^4 times, in
# the four cases of Fig. 9b (original, twist, shear, both).
#
# The step.  The reference runs every case at one step (Table 8: 75 ns).
# Hardening the scaffold's shear cuts the explicit stable estimate from
# 481 ns to 133 ns (the front feet's shear-rotation mode), so the four cases
# run at 66.66 ns, half the hardened estimate (the simulator's default for
# shear and both: 10 ms / 150005 steps).  The original runs again at its own
# default, 241 ns, and at half that, 120 ns: how far the original's walk
# moves with the step says how large a difference between cases the step
# alone can make (the feet's stick-slip is sensitive).
#
# Then the original and the shear-hardened walker at half the common step,
# 33.33 ns: whether their difference is the hardening's or the step's; and
# the scaffold's shear hardened alone and the muscle's alone: which part's
# hardening slows the walker (docs/validation.md: the scaffold's feet).
#
# And the original and the shear-hardened walker on a damped dish
# (dish_damping = 0.1 kg/s, a quarter to a third of critical for a foot element on its
# contact spring, against Table 8's 1e-6 kg/s): whether the feet's hopping
# on the undamped dish is what separates them (docs/validation.md).
#
# BUDGET full: the reference's 10 s (20 strokes), all twelve runs; quick:
# 1 s, two strokes, for the four cases, and one stroke (0.5 s) on the damped
# dish (about 90 s of one core per simulated second unloaded, 4 min of wall
# time on two cores).  A stroke's twitch is where the cases part (the feet's
# contact while the muscle contracts), and the first stroke is not the walk:
# the shear-hardened walker slides back in it and forward in the second.
# WALKER_DURATION overrides the duration (a time with its unit),
# WALKER_CHECK_DURATION that of the two runs at half the step (default: the
# same), WALKER_DISH_DURATION that of the two on the damped dish.
# scripts/reproduce/walker_report.py measures the runs and writes
# rows.jsonl, meta.json and the plot.
set -e
BUDGET=${1:?usage: walker.sh quick|full OUTDIR}
OUTDIR=${2:?usage: walker.sh quick|full OUTDIR}
case $BUDGET in
quick) DUR=1s; DISHDUR=0.5s ;;
full) DUR=10s; DISHDUR=10s ;;
*) echo "walker.sh: budget must be quick or full, not '$BUDGET'" >&2; exit 2 ;;
esac
DUR=${WALKER_DURATION:-$DUR}
CHECK=${WALKER_CHECK_DURATION:-$DUR}
DISHDUR=${WALKER_DISH_DURATION:-$DISHDUR}
mkdir -p "$OUTDIR"
: > "$OUTDIR/commands.txt"
. scripts/reproduce/runs.sh
SIM=$OUTDIR/walker
echo "bin/sinewc examples/walker.sinew -o $SIM" >> "$OUTDIR/commands.txt"
bin/sinewc examples/walker.sinew -o "$SIM"
TWIST="--set scaffold_twist=1e4 --set muscle_twist=10"
SHEAR="--set scaffold_shear=1e4 --set muscle_shear=10"
DT="--dt 6.666444451851605e-08"     # 10 ms / 150005: shear's and both's default
# the longest runs first, so that the two slots stay busy
run both $SIM --duration $DUR $TWIST $SHEAR
run shear $SIM --duration $DUR $SHEAR
run twist $SIM --duration $DUR $DT $TWIST
run original $SIM --duration $DUR $DT
DISH="--set dish_damping=0.1kg/s"
run shear_dish $SIM --duration $DISHDUR $SHEAR $DISH
run original_dish $SIM --duration $DISHDUR $DT $DISH
if [ "$BUDGET" = full ]; then
  run original_dt120 $SIM --duration $DUR --dt 120.366ns
  run original_dt241 $SIM --duration $DUR
  run original_dt33 $SIM --duration $CHECK --dt 3.333222225925803e-08
  run shear_dt33 $SIM --duration $CHECK --dt 3.333222225925803e-08 $SHEAR
  run shear_scaffold $SIM --duration $DUR --set scaffold_shear=1e4
  run shear_muscle $SIM --duration $DUR $DT --set muscle_shear=10
fi
finish
/usr/bin/python3 scripts/reproduce/walker_report.py "$BUDGET" "$OUTDIR"
