#!/bin/sh
# bench_snake_eval.sh OLD_REV [ROUNDS] — the muscular snake's time to
# solution (issue 31): one whole 5 s evaluation of the four-pair study scene
# (examples/study/snake_pairs4.sinew) and the four-pair example
# (examples/snake_muscular.sinew), each as the code at OLD_REV writes it
# (its scene files, its step, its compiler and runtime: a worktree of it,
# bench_base.sh) and as this tree does, run
# interleaved ROUNDS times (default 5; the order alternates from round to
# round), one thread.  Prints the medians of the process's CPU time (user +
# system, start-up included; on a machine whose cores are shared the wall
# time also counts the waits for a core, so it is given too), the steps,
# and each run's result: the study scene's objective, the example's speed
# over 1-5 s (from its centre-of-mass probe), both against a run of this
# tree at 10 us.
set -eu
old=$1 rounds=${2:-5}
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/old" "$tmp/new"
. bench/bench_base.sh
tree=$root/build/bench/base-$old
bench_base "$tree" "$old"
for s in pairs4:study/snake_pairs4 example:snake_muscular; do
  (cd "$tree" && SINEW_PATH="$tree/models" bin/sinewc "examples/${s#*:}.sinew" -o "$tmp/old/${s%%:*}")
  SINEW_PATH="$root/models" "$root/bin/sinewc" "$root/examples/${s#*:}.sinew" -o "$tmp/new/${s%%:*}"
done
speed() { # speed FILE.h5: the example's mean speed over 1-5 s, m/s
  /usr/bin/python3 -c "
import h5py, numpy as np
f = h5py.File('$1', 'r'); t = f['time'][:]; c = f['probes/com'][:]
i, j = abs(t - 1).argmin(), abs(t - 5).argmin()
print('%.9f' % ((c[j, 0] - c[i, 0]) / (t[j] - t[i])))"
}
result() { # result SCENE LOG H5
  if [ "$1" = pairs4 ]; then sed -n 's/.*objective: .* = \([-0-9.e+]*\) m\/s;.*/\1/p' "$2"; else speed "$3"; fi
}
run() { # run WHICH SCENE [ARGS]: appends "cpu wall steps result" to $tmp/WHICH.SCENE
  w=$1 s=$2
  shift 2
  /usr/bin/time -f 'cpu %U %S' -o "$tmp/time" "$tmp/$w/$s" "$@" --out "$tmp/$w.$s.h5" > "$tmp/log" 2>&1
  set -- $(awk '$1 == "cpu" { print $2 + $3 }' "$tmp/time") \
    $(sed -n 's/.* in \([0-9.e+-]*\) s wall time (\([0-9]*\) steps).*/\1 \2/p' "$tmp/log") \
    $(result "$s" "$tmp/log" "$tmp/$w.$s.h5")
  echo "$*" >> "$tmp/$w.$s"
}
for s in pairs4 example; do run new "$s" --dt 10us; mv "$tmp/new.$s" "$tmp/fine.$s"; done
r=0
while [ $r -lt "$rounds" ]; do
  for s in pairs4 example; do
    if [ $((r % 2)) -eq 0 ]; then run old $s; run new $s; else run new $s; run old $s; fi
  done
  r=$((r + 1))
done
median() { sort -g -k"$2" "$1" | awk -v k="$2" '{ w[NR] = $k } END {
  printf "%.3f", NR % 2 ? w[(NR + 1) / 2] : (w[NR / 2] + w[NR / 2 + 1]) / 2 }'; }
echo "CPU: $(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -1), $(nproc) logical CPUs; load average $(cut -d' ' -f1-3 /proc/loadavg); old $(git -C "$root" rev-parse --short "$old"), new $(git -C "$root" rev-parse --short HEAD)$(git -C "$root" diff --quiet HEAD -- runtime examples models || echo ' (modified)')"
printf '%-8s %-4s %7s %9s %9s %14s %10s\n' scene code steps "CPU s" "wall s" result "vs 10 us"
for s in pairs4 example; do
  fine=$(cut -d' ' -f4 "$tmp/fine.$s")
  for w in old new; do
    awk -v s=$s -v w=$w -v c="$(median "$tmp/$w.$s" 1)" -v wl="$(median "$tmp/$w.$s" 2)" -v f="$fine" \
      '{ n = $3; r = $4 } END { printf "%-8s %-4s %7d %9.3f %9.3f %14.10f %10.2e\n", s, w, n, c, wl, r, (r - f) / f }' "$tmp/$w.$s"
  done
done
