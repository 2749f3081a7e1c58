#!/bin/sh
# study_snake.sh — the muscular snake's bottom-up study (Zhang et al. 2019,
# Supplementary Note 4, Fig. 2): for 1 to 5 muscle-tendon pairs, and for the
# continuum snake the muscular ones are measured against, CMA-ES looks for
# the design that crawls fastest (examples/study/*.sinew: the params with
# ranges and the objective are in the scenes).
#
#   scripts/study_snake.sh [--budget N] [--np N] [--out DIR] [ARCH ...]
#   scripts/study_snake.sh --chain [--sigma F] [--budget N] [--np N] [--out DIR]
#
# ARCH: continuum, 1, 2, 3, 4, 5 (default: all six).  Each optimisation runs
# under `mpirun -np N` (default 2: every core of this machine) with seed 1
# and writes DIR/ARCH_study.h5 (default DIR: study/) as its results arrive.
# A study file that exists is continued (--resume), so an interrupted study
# picks up where it stopped, and one that spent its budget runs on when a
# larger --budget is asked for (CMA-ES continues its generations: the same
# result as one run with that budget); a complete one is left as it is.
# The best-design runs of the report (DIR/best_*.h5) are made again after
# a study has run.  DIR/walltime.txt gets a line per run:
# ARCH, ranks, budget, wall seconds, evaluations.  Then
# scripts/study_snake_report.py writes the table and plots of
# docs/validation.md ("The muscular snake's study"), the plots into
# $STUDY_IMG when it is set, else docs/img.
#
# --chain: the same question asked pair by pair.  An n-pair design is
# nearly an (n+1)-pair design whose extra pair pulls with 0 N (the idle
# pair's mass, stiffness and damping cost 1-2% of the speed from two pairs
# up: docs/validation.md), so a stage starts next to a good design.  The
# chain runs the
# 1-pair study (DIR/1_study.h5), then for n = 2..5 an optimisation
# (DIR/n_chain.h5) that starts (--start) at the best (n-1)-pair design
# found so far (of DIR/(n-1)_study.h5 and DIR/(n-1)_chain.h5, whichever
# scored higher), its new pair at 20 N, with a smaller step (--sigma,
# default 0.15).  DIR/chain_sources.txt records where each stage started.
set -e
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUDGET=300
NP=2
OUT=study
CHAIN=0
SIGMA=0.15
while [ $# -gt 0 ]; do
  case $1 in
  --chain) CHAIN=1; shift ;;
  --sigma) SIGMA=$2; shift 2 ;;
  --budget) BUDGET=$2; shift 2 ;;
  --np) NP=$2; shift 2 ;;
  --out) OUT=$2; shift 2 ;;
  --*) echo "study_snake: unknown option $1" >&2; exit 2 ;;
  *) break ;;
  esac
done
if [ $CHAIN = 1 ]; then
  [ $# -eq 0 ] || { echo "study_snake: --chain runs 1 to 5 pairs in order; no ARCH" >&2; exit 2; }
  ARCHS="1 2 3 4 5"
else
  ARCHS=${*:-continuum 1 2 3 4 5}
fi
PY=/usr/bin/python3
# best_score FILE: the best score a study file holds (-inf if none yet)
best_score() {
  HDF5_USE_FILE_LOCKING=FALSE $PY -c "import h5py,sys; f=h5py.File(sys.argv[1],'r'); print(f['best'].attrs['score'] if 'best' in f else '-inf')" "$1" 2>/dev/null || echo -inf
}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
command -v mpirun >/dev/null || { echo "study_snake: mpirun is not installed (make deps installs openmpi-bin)" >&2; exit 1; }
mkdir -p "$OUT"
for a in $ARCHS; do
  case $a in
  continuum) scene=snake_continuum_opt ;;
  [1-5]) scene=snake_pairs$a ;;
  *) echo "study_snake: unknown architecture '$a' (continuum, 1 to 5)" >&2; exit 2 ;;
  esac
  sim=$OUT/$scene
  SINEW_PATH=$ROOT/models "$ROOT/bin/sinewc" "$ROOT/examples/study/$scene.sinew" -o "$sim"
  file=$OUT/${a}_study.h5
  tag=$a
  set --
  if [ $CHAIN = 1 ] && [ "$a" != 1 ]; then
    # start at the best design of one pair fewer, the new pair at 20 N
    p=$((a - 1)) src=
    for f in "$OUT/${p}_study.h5" "$OUT/${p}_chain.h5"; do
      [ -e "$f" ] || continue
      if [ -z "$src" ] || $PY -c "import sys; sys.exit(not float(sys.argv[1]) > float(sys.argv[2]))" \
          "$(best_score "$f")" "$(best_score "$src")"; then src=$f; fi
    done
    [ -n "$src" ] || { echo "study_snake: no $p-pair study in $OUT to start the chain's $a pairs from" >&2; exit 1; }
    file=$OUT/${a}_chain.h5
    tag=${a}c
    set -- --start "$src" --start "amp$a=20 N" --sigma "$SIGMA"
    [ -e "$file" ] || echo "$a $(basename "$src") $(best_score "$src")" >> "$OUT/chain_sources.txt"
  fi
  state=$( [ -e "$file" ] && /usr/bin/python3 -c "import h5py,sys; print(h5py.File(sys.argv[1])['/'].attrs['status'])" "$file" 2>/dev/null || echo none)
  had=$( [ -e "$file" ] && /usr/bin/python3 -c "import h5py,sys; print(int(h5py.File(sys.argv[1])['/'].attrs['samples']))" "$file" 2>/dev/null || echo 0)
  # a study that spent its budget runs on when asked for a larger one
  case $state in "complete: the budget"*) [ "$BUDGET" -gt "$had" ] && state="budget $had" ;; esac
  t0=$(date +%s.%N)
  case $state in
  none)
    echo "study_snake: $scene, CMA-ES, budget $BUDGET, $NP ranks -> $file${1:+ (from $2)}"
    mpirun -np "$NP" "$sim" --optimize --budget "$BUDGET" --seed 1 "$@" --study "$file" --quiet || true ;;
  "budget "*)
    echo "study_snake: $file spent its budget of $had evaluations; running on to $BUDGET"
    mpirun -np "$NP" "$sim" --resume "$file" --budget "$BUDGET" --quiet || true ;;
  complete*)
    echo "study_snake: $file is complete; left as it is" ;;
  *)
    echo "study_snake: continuing $file ($state)"
    mpirun -np "$NP" "$sim" --resume "$file" --quiet || true ;;
  esac
  t1=$(date +%s.%N)
  case $state in complete*) ;; *)
    rm -f "$OUT/best_$tag.h5" "$OUT/best_$tag.xdmf" "$OUT/best_${tag}_10us.h5" "$OUT/best_${tag}_10us.xdmf"
    n=$(/usr/bin/python3 -c "import h5py,sys; print(len(h5py.File(sys.argv[1])['evaluations/score']))" "$file")
    awk -v a="$tag" -v np="$NP" -v b="$BUDGET" -v t0="$t0" -v t1="$t1" -v n="$n" \
      'BEGIN {printf "%s %d %d %.1f %d\n", a, np, b, t1 - t0, n}' >> "$OUT/walltime.txt" ;;
  esac
done
/usr/bin/python3 "$ROOT/scripts/study_snake_report.py" "$OUT" --img "${STUDY_IMG:-docs/img}"
