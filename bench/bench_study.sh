#!/bin/sh
# bench_study.sh — evaluations per second of a study with 1 and 2 MPI ranks
# (and 4, oversubscribed on this 2-core machine): the optimisation of
# tests/lang/test_optimize.sh's dropped rod at dt = 2 us (50 000 steps an
# evaluation), 300 evaluations, each configuration run REPEAT times,
# interleaved, the median wall time reported.  Then the same for a real
# study: 24 evaluations (3 generations of 8) of the one-pair muscular snake
# (examples/study/snake_pairs1.sinew, 5 s at dt = 20 us each, issue 13)
# with 1 and 2 ranks, REPEAT_SNAKE times (default 1: ~4 min).  Prints two
# Markdown tables.  The studies run with --no-recheck: the figures are the
# study's evaluations, without the recheck of its best designs at dt/2 that
# follows them.
set -e
ROOT=$(cd "$(dirname "$0")/.." && pwd)
REPEAT=${REPEAT:-3}
TMP=$(mktemp -d "${TMPDIR:-/tmp}/sinew-bench-study.XXXXXX")
trap 'rm -rf "$TMP"' EXIT INT TERM
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
sed -n '/^cat > "\$TMP\/drop.sinew"/,/^EOF/p' "$ROOT/tests/lang/test_optimize.sh" | sed '1d;$d' \
  > "$TMP/drop.sinew"
"$ROOT/bin/sinewc" "$TMP/drop.sinew" -o "$TMP/drop"
command -v mpirun >/dev/null || { echo "bench_study: mpirun is not installed" >&2; exit 1; }
cd "$TMP"
for r in $(seq "$REPEAT"); do
  for np in 1 2 4; do
    rm -f s.h5
    t0=$(date +%s.%N)
    mpirun -np $np ./drop --optimize --budget 300 --seed 5 --dt 2us --study s.h5 --quiet --no-recheck
    t1=$(date +%s.%N)
    awk -v n=$np -v a="$t0" -v b="$t1" 'BEGIN {print n, b - a}' >> times
  done
done
echo "| ranks | evaluations | wall time (median of $REPEAT) | evaluations per second |"
echo "|--:|--:|--:|--:|"
for np in 1 2 4; do
  med=$(awk -v n=$np '$1 == n {print $2}' times | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}')
  n=$(/usr/bin/python3 -c "import h5py; print((h5py.File('s.h5')['evaluations/status'][()]!=0).sum())")
  awk -v np=$np -v n="$n" -v t="$med" 'BEGIN {printf "| %d | %d | %.2f s | %.0f |\n", np, n, t, n / t}'
done

# ---- the muscular snake: seconds per evaluation ----
REPEAT_SNAKE=${REPEAT_SNAKE:-1}
SINEW_PATH="$ROOT/models" "$ROOT/bin/sinewc" "$ROOT/examples/study/snake_pairs1.sinew" -o snake1
: > stimes
for r in $(seq "$REPEAT_SNAKE"); do
  for np in 1 2; do
    rm -f sn.h5
    t0=$(date +%s.%N)
    mpirun -np $np ./snake1 --optimize --budget 24 --seed 1 --study sn.h5 --quiet --no-recheck
    t1=$(date +%s.%N)
    awk -v n=$np -v a="$t0" -v b="$t1" 'BEGIN {print n, b - a}' >> stimes
  done
done
echo
echo "| muscular snake, 1 pair (5 s an evaluation) | ranks | evaluations | wall time (median of $REPEAT_SNAKE) | evaluations per second |"
echo "|---|--:|--:|--:|--:|"
for np in 1 2; do
  med=$(awk -v n=$np '$1 == n {print $2}' stimes | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}')
  n=$(/usr/bin/python3 -c "import h5py; print((h5py.File('sn.h5')['evaluations/status'][()]!=0).sum())")
  awk -v np=$np -v n="$n" -v t="$med" 'BEGIN {printf "| snake_pairs1 | %d | %d | %.1f s | %.3f |\n", np, n, t, n / t}'
done
