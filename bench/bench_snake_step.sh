#!/bin/sh
# bench_snake_step.sh OLD_REV [ROUNDS] — the muscular snake's step (issue
# 31) and two scenes that must not get slower, built by the code at OLD_REV
# (git archive into a temporary tree, its own `make bin/sinewc`) and by this
# tree's bin/sinewc, run interleaved ROUNDS times (default 5; the order
# alternates from round to round), one thread.  Prints the medians of the
# simulator's own wall time ("in X s wall time": the run loop, output
# included, start-up not) and of the process's CPU time (user + system,
# start-up included: on a machine whose cores are shared with other jobs
# the wall time also counts the waits for a core), the cost per step of
# each, and whether the two outputs of the last round are bitwise equal
# (h5diff).
#   snake:     examples/snake_muscular.sinew, --duration 0.5s (dt = 20 us)
#   elbow:     examples/elbow_flexion.sinew, --integrator imex --dt 1.8us --duration 0.05s
#   continuum: examples/snake_continuum.sinew, --duration 0.5s (dt = 10 us)
set -eu
old=$1 rounds=${2:-5}
root=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/tree" "$tmp/old" "$tmp/new"
git -C "$root" archive "$old" | tar -x -C "$tmp/tree"
make -C "$tmp/tree" -j1 bin/sinewc >/dev/null 2>&1
for s in snake:snake_muscular elbow:elbow_flexion continuum:snake_continuum; do
  "$tmp/tree/bin/sinewc" "$root/examples/${s#*:}.sinew" -o "$tmp/old/${s%%:*}"
  "$root/bin/sinewc" "$root/examples/${s#*:}.sinew" -o "$tmp/new/${s%%:*}"
done
args() {
  case $1 in
    snake|continuum) echo "--duration 0.5s" ;;
    elbow) echo "--integrator imex --dt 1.8us --duration 0.05s" ;;
  esac
}
run() { # run WHICH SCENE: appends "wall steps" to $tmp/WHICH.SCENE, "cpu steps" to $tmp/WHICH.SCENE.cpu
  /usr/bin/time -f 'cpu %U %S' -o "$tmp/time" "$tmp/$1/$2" $(args "$2") --out "$tmp/$1.$2.h5" > "$tmp/log" 2>&1
  sed -n 's/.* in \([0-9.e+-]*\) s wall time (\([0-9]*\) steps).*/\1 \2/p' "$tmp/log" >> "$tmp/$1.$2"
  awk -v n="$(tail -1 "$tmp/$1.$2" | cut -d' ' -f2)" '$1 == "cpu" { print $2 + $3, n }' "$tmp/time" >> "$tmp/$1.$2.cpu"
}
r=0
while [ $r -lt "$rounds" ]; do
  for s in snake elbow continuum; do
    if [ $((r % 2)) -eq 0 ]; then run old $s; run new $s; else run new $s; run old $s; fi
  done
  r=$((r + 1))
done
median() { sort -g "$1" | awk '{ w[NR] = $1; s = $2 } END {
  m = NR % 2 ? w[(NR + 1) / 2] : (w[NR / 2] + w[NR / 2 + 1]) / 2; printf "%.3f %d", m, s }'; }
echo "CPU: $(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -1), $(nproc) logical CPUs; old $(git -C "$root" rev-parse --short "$old"), new $(git -C "$root" rev-parse --short HEAD)$(git -C "$root" diff --quiet HEAD -- runtime || echo ' (modified)')"
printf '%-10s %-4s %6s %10s %11s %10s %11s %8s  %s\n' scene time steps "old s" "old us/step" "new s" "new us/step" new/old outputs
for s in snake elbow continuum; do
  same=$(h5diff -q "$tmp/old.$s.h5" "$tmp/new.$s.h5" >/dev/null 2>&1 && echo bitwise || echo differ)
  for t in wall cpu; do
    x=$([ $t = cpu ] && echo .cpu || true)
    set -- $(median "$tmp/old.$s$x") $(median "$tmp/new.$s$x")
    awk -v s=$s -v t=$t -v ow="$1" -v n="$2" -v nw="$3" -v same=$same 'BEGIN {
      printf "%-10s %-4s %6d %10.3f %11.2f %10.3f %11.2f %8.3f  %s\n", s, t, n, ow, 1e6 * ow / n, nw, 1e6 * nw / n, nw / ow, same }'
  done
done
