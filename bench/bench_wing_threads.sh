#!/bin/sh
# bench_wing_threads.sh OLD_REV [ROUNDS] [DURATION] — the kinematic wing
# (models/pigeon_wing.sinew) on one thread and on two, as the code at
# OLD_REV builds it (a worktree of it, bench_base.sh) and as this tree does:
# the four run interleaved ROUNDS times (default 5; the order alternates),
# each for DURATION of the stroke (default 5 ms) at the model's step, less a
# 0 s run of the same simulator on the same threads (start-up: building
# 3177 rods and their stability limits).  Prints the medians of wall time per
# step (what a user waits for; CPU time on two threads counts both), and
# whether each build's two-thread run gives the bits of its one-thread run
# (--compare --rtol 0 over every dataset).  Run it on an otherwise idle
# machine: two threads take both of a two-core machine's processors.
set -eu
old=$1 rounds=${2:-5} dur=${3:-5ms}
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
. bench/bench_base.sh
bench_old_tree "$old"
(cd "$tree" && SINEW_PATH="$tree/models" bin/sinewc models/pigeon_wing.sinew -o "$tmp/old") > /dev/null
SINEW_PATH="$root/models" "$root/bin/sinewc" "$root/models/pigeon_wing.sinew" -o "$tmp/new" > /dev/null
wall() { # wall BIN THREADS DURATION: the run's wall seconds
  /usr/bin/time -f 'wall %e' -o "$tmp/time" "$tmp/$1" --quiet --threads "$2" --duration "$3" --every "$3" \
    --out "$tmp/$1-$2.h5" > /dev/null 2>&1 || echo "# $1 on $2 threads failed" >&2
  awk '$1 == "wall" { print $2 }' "$tmp/time"
}
steps=$(bench_steps "$tmp/new" "$dur")
r=0
while [ $r -lt "$rounds" ]; do
  for w in $([ $((r % 2)) -eq 0 ] && echo old new || echo new old); do
    for t in 1 2; do
      z=$(wall $w $t 0)
      c=$(wall $w $t "$dur")
      echo "$c $z" | awk -v n="$steps" '{ printf "%.6f\n", ($1 - $2) / n }' >> "$tmp/$w.$t"
    done
  done
  r=$((r + 1))
done
median() { sort -g "$1" | awk '{ w[NR] = $1 } END {
  printf "%.3f", 1e3 * (NR % 2 ? w[(NR + 1) / 2] : (w[NR / 2] + w[NR / 2 + 1]) / 2) }'; }
same() { # same BIN: does its two-thread run give the bits of its one-thread run
  "$tmp/$1" --quiet --threads 2 --duration "$dur" --every "$dur" --out "$tmp/$1-same.h5" \
    --compare "$tmp/$1-1.h5" --rtol 0 2>&1 | sed -n 's/.*compare: //p' | tail -1; }
echo "CPU: $(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -1), $(nproc) logical CPUs;" \
     "load average $(cut -d' ' -f1-3 /proc/loadavg); old $(git -C "$root" rev-parse --short "$old")," \
     "new $(git -C "$root" rev-parse --short HEAD)$(git -C "$root" diff --quiet HEAD -- runtime models || echo ' (modified)');" \
     "$dur ($steps steps), $rounds rounds"
printf '%-4s %18s %18s %8s   %s\n' code "1 thread, ms/step" "2 threads, ms/step" "2 vs 1" "2 threads against 1, --rtol 0"
for w in old new; do
  a=$(median "$tmp/$w.1") b=$(median "$tmp/$w.2")
  printf '%-4s %18s %18s %8s   %s\n' $w "$a" "$b" "$(echo "$a $b" | awk '{ printf "%.2fx", $1 / $2 }')" "$(same $w)"
done
