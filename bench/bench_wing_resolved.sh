#!/bin/sh
# bench_wing_resolved.sh OLD_REV [ROUNDS] — the fully resolved wing's step
# (models/pigeon_wing_resolved.sinew, issue 32): its CPU time per step as
# the code at OLD_REV builds it (its model file, compiler and runtime: a
# worktree of it, bench_base.sh) and as this tree does, the two run
# interleaved ROUNDS times (default 3; the order alternates), one thread,
# each for 1 ms of the stroke at 0.3 us (3333 steps: the step at which the
# wing ran before it ran at 1 us) less a 0 s run of the same simulator
# (start-up: building 3177 rods); and this tree's at 1 us (1000 steps).
# Prints the medians, and each run's elbow hinge angle (rad) after 1 ms against this
# tree's at 0.3 us.
set -eu
old=$1 rounds=${2:-3}
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
. bench/bench_base.sh
bench_old_tree "$old"
(cd "$tree" && SINEW_PATH="$tree/models" bin/sinewc models/pigeon_wing_resolved.sinew -o "$tmp/old")
SINEW_PATH="$root/models" "$root/bin/sinewc" "$root/models/pigeon_wing_resolved.sinew" -o "$tmp/new"
cpu() { # cpu BIN ARGS: the run's user + system seconds
  b=$1
  shift
  /usr/bin/time -f 'cpu %U %S' -o "$tmp/time" "$tmp/$b" --quiet "$@" --out "$tmp/$b.h5" \
    > /dev/null 2>&1 || echo "# $b $* failed" >&2
  awk '$1 == "cpu" { print $2 + $3 }' "$tmp/time"
}
elbow() { /usr/bin/python3 -c "
import h5py; print('%.9f' % h5py.File('$tmp/$1.h5', 'r')['/joints/elbow/angle'][-1])"; }
r=0
while [ $r -lt "$rounds" ]; do
  for w in $([ $((r % 2)) -eq 0 ] && echo old new || echo new old); do
    z=$(cpu $w --duration 0)
    c=$(cpu $w --dt 0.3us --duration 1ms --every 1ms)
    echo "$(echo "$c $z" | awk '{ printf "%.6f", ($1 - $2) / 3333 }') $(elbow $w)" >> "$tmp/$w.03"
  done
  z=$(cpu new --duration 0)
  c=$(cpu new --dt 1us --duration 1ms --every 1ms)
  echo "$(echo "$c $z" | awk '{ printf "%.6f", ($1 - $2) / 1000 }') $(elbow new)" >> "$tmp/new.1"
  r=$((r + 1))
done
median() { sort -g "$1" | awk '{ w[NR] = $1 } END {
  printf "%.3f", 1e3 * (NR % 2 ? w[(NR + 1) / 2] : (w[NR / 2] + w[NR / 2 + 1]) / 2) }'; }
echo "CPU: $(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -1), $(nproc) logical CPUs; load average $(cut -d' ' -f1-3 /proc/loadavg); old $(git -C "$root" rev-parse --short "$old"), new $(git -C "$root" rev-parse --short HEAD)$(git -C "$root" diff --quiet HEAD -- runtime models || echo ' (modified)')"
ref=$(head -1 "$tmp/new.03" | cut -d' ' -f2)
printf '%-4s %-6s %14s %26s\n' code step "ms CPU a step" "elbow hinge at 1 ms (rad)"
for x in old:03 new:03 new:1; do
  f=$tmp/$(echo $x | tr : .)
  printf '%-4s %-6s %14s %26s\n' "${x%%:*}" "$([ "${x#*:}" = 03 ] && echo 0.3us || echo 1us)" \
    "$(median "$f")" "$(head -1 "$f" | cut -d' ' -f2) ($(head -1 "$f" | cut -d' ' -f2 | awk -v r="$ref" '{ printf "%+.1e", $1 - r }'))"
done
