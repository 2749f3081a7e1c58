#!/bin/sh
# wing.sh — `make reproduce` module: the feathered wing hardened and
# softened (Zhang et al. 2019, Suppl. Notes 5 and 6.7, Fig. 13), by
# scripts/wing_study.sh (`make wing`) on models/pigeon_wing.sinew: the
# original, (b) every rod's twist and shear x10, (c) the muscles' shear and
# twist /5, (d) their twist alone /5.  quick: the first 0.15 s of the 0.51 s
# stroke (the initiation phase and the start of the downstroke; about 3 min
# a run); full: the whole stroke (about 10 min a run on an idle core, the
# hardened ones up to 45 min).
#   scripts/reproduce/wing.sh quick|full OUTDIR
set -eu
BUDGET=$1 OUT=$2
case $BUDGET in
  quick) sh scripts/wing_study.sh --out "$OUT" --duration 0.15s original soft soft_twist hard ;;
  full) sh scripts/wing_study.sh --out "$OUT" original soft soft_twist hard ;;
  *) echo "budget: quick or full" >&2; exit 2 ;;
esac
[ -f "$OUT/original.h5" ] || { echo "wing.sh: the original wing did not run"; exit 1; }
/usr/bin/python3 scripts/reproduce/wing_report.py "$OUT" "$BUDGET"
