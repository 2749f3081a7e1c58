#!/bin/sh
# snake_muscular.sh — `make reproduce` module: the muscular snake's
# bottom-up study (Zhang et al. 2019, Suppl. Note 4, Figs. 2-3) by
# scripts/study_snake.sh (`make study-snake`): CMA-ES over 1 to 5
# muscle-tendon pairs and over the continuum snake they are measured
# against, under mpirun on every core, seed 1.  quick: 32 evaluations per
# architecture (CMA-ES's first generations only: the reference ran
# thousands); full: 300 each, then the chained study (each stage started at
# the best design with one pair fewer), 250 each.
#   scripts/reproduce/snake_muscular.sh quick|full OUTDIR
set -eu
BUDGET=$1 OUT=$2
export STUDY_IMG="$OUT"   # the study's own plots stay with this run, not in docs/img
case $BUDGET in
  quick) sh scripts/study_snake.sh --budget 32 --out "$OUT" ;;
  full) sh scripts/study_snake.sh --budget 300 --out "$OUT"
        sh scripts/study_snake.sh --chain --budget 250 --out "$OUT" ;;
  *) echo "budget: quick or full" >&2; exit 2 ;;
esac
/usr/bin/python3 scripts/reproduce/snake_muscular_report.py "$OUT" "$BUDGET"
