#!/bin/sh
# swimmer.sh BUDGET OUTDIR — twist and shear hardening of the cell-powered
# flagella swimmer (Zhang et al. 2019, Suppl. Note 6.3, Table 7, Fig. 8):
# the twist and shear stiffness of substrate and cell hardened 100 times, in
# the four cases of Fig. 8b (original, twist, shear, both).
#
# Hardening the tail's shear 100 times cuts its explicit stable step tenfold
# (82 ns to 8.4 ns: the shear-rotation mode, r / c), so the four cases run
# with the substrate implicit (sinewc --let implicit=true, --integrator imex)
# at the scene's 80 ns, all four alike; the scene as written (explicit
# Verlet) runs once more, the original, to measure what the scheme changes.
#
# BUDGET full: the reference's 6.5 s (23 beats); quick: 0.14 s, the first
# half beat (the cell's first contraction).  SWIMMER_DURATION overrides the
# duration (a time with its unit).  scripts/reproduce/swimmer_report.py
# measures the runs and writes rows.jsonl, meta.json and the plot.
set -e
BUDGET=${1:?usage: swimmer.sh quick|full OUTDIR}
OUTDIR=${2:?usage: swimmer.sh quick|full OUTDIR}
case $BUDGET in
quick) DUR=0.14s ;;
full) DUR=6.5s ;;
*) echo "swimmer.sh: budget must be quick or full, not '$BUDGET'" >&2; exit 2 ;;
esac
DUR=${SWIMMER_DURATION:-$DUR}
mkdir -p "$OUTDIR"
: > "$OUTDIR/commands.txt"
. scripts/reproduce/runs.sh
SIM=$OUTDIR/swimmer
IMP=$OUTDIR/swimmer_implicit
echo "bin/sinewc examples/flagella_swimmer.sinew -o $SIM" >> "$OUTDIR/commands.txt"
echo "bin/sinewc examples/flagella_swimmer.sinew --let implicit=true -o $IMP" >> "$OUTDIR/commands.txt"
bin/sinewc examples/flagella_swimmer.sinew -o "$SIM"
bin/sinewc examples/flagella_swimmer.sinew --let implicit=true -o "$IMP"
TWIST="--set twist=100 --set cell_twist=100"
SHEAR="--set shear=100 --set cell_shear=100"
run both $IMP --integrator imex --duration $DUR $TWIST $SHEAR
run shear $IMP --integrator imex --duration $DUR $SHEAR
run twist $IMP --integrator imex --duration $DUR $TWIST
run original $IMP --integrator imex --duration $DUR
run original_explicit $SIM --duration $DUR
finish
/usr/bin/python3 scripts/reproduce/swimmer_report.py "$BUDGET" "$OUTDIR"
