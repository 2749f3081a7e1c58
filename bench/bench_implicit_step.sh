#!/bin/sh
# bench_implicit_step.sh OLD_REV [ROUNDS] — the implicit rod step (issue 31):
# the cost per step of the hardened snake (examples/snake_hardening.sinew,
# x25) with implicit = true against the same scene with implicit = false,
# both under integrator = imex at the same dt (0.8 of the explicit scene's
# stable estimate), for n = 50, 100 and 200 elements (models/
# continuum_snake.sinew with its element count changed, in a temporary
# copy); built by the code at OLD_REV (git archive into a temporary tree,
# its own `make bin/sinewc`) and by this tree's bin/sinewc, run interleaved
# ROUNDS times (default 5; the order alternates from round to round), one
# thread.  The cost per step is the process's CPU time (user + system: on a
# machine whose cores are shared, the wall time also counts the waits for a
# core) less that of the same simulator run for 0 s (start-up and output),
# over the steps; medians over the rounds.  Prints a markdown table: both
# costs, their ratio (implicit / explicit) old and new, and how far the new
# implicit run's output moved from the old one's (scripts/compare_h5.py).
set -eu
old=$1 rounds=${2:-5}
root=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/tree" "$tmp/cpu"
git -C "$root" archive "$old" | tar -x -C "$tmp/tree"
make -C "$tmp/tree" -j1 bin/sinewc >/dev/null 2>&1
sizes="50 100 200"
for n in $sizes; do
  mkdir -p "$tmp/m$n"
  cp "$root"/models/*.sinew "$tmp/m$n/"
  sed -i "s/elements = 50;/elements = $n;/" "$tmp/m$n/continuum_snake.sinew"
  grep -q "elements = $n;" "$tmp/m$n/continuum_snake.sinew"
  for w in old new; do
    c=$([ $w = old ] && echo "$tmp/tree/bin/sinewc" || echo "$root/bin/sinewc")
    SINEW_PATH="$tmp/m$n" "$c" "$root/examples/snake_hardening.sinew" -o "$tmp/$w.exp.$n"
    SINEW_PATH="$tmp/m$n" "$c" --let implicit=true "$root/examples/snake_hardening.sinew" -o "$tmp/$w.imp.$n"
  done
  # dt: 0.8 of the explicit scene's stable estimate, in us; 20000 steps at n = 50 (SW_BENCH_STEPS), fewer in proportion above
  est=$("$tmp/new.exp.$n" --info | sed -n 's/^dt: .*stable estimate \([0-9.e+-]*\) \([a-z]*\)).*/\1 \2/p')
  dt=$(echo "$est" | awk '{ f = $2 == "ns" ? 1e-3 : $2 == "us" ? 1 : $2 == "ms" ? 1e3 : 1e6; printf "%.3f", 0.8 * $1 * f }')
  steps=$((${SW_BENCH_STEPS:-20000} * 50 / n))
  echo "$dt $steps" > "$tmp/run.$n"
done
run() { # run WHO KIND N DURATION: appends the CPU seconds to $tmp/cpu/WHO.KIND.N[.0]
  set -- "$1" "$2" "$3" "$4" $(cat "$tmp/run.$3")
  x=$([ "$4" = 0 ] && echo .0 || true)
  /usr/bin/time -f '%U %S' -o "$tmp/time" "$tmp/$1.$2.$3" --integrator imex --dt "$5us" --duration "$4" \
    --quiet --out "$tmp/out.$1.$2.$3$x.h5" >/dev/null 2>&1
  awk '{ print $1 + $2 }' "$tmp/time" >> "$tmp/cpu/$1.$2.$3$x"
}
r=0
while [ $r -lt "$rounds" ]; do
  for n in $sizes; do
    set -- $(cat "$tmp/run.$n")
    dur=$(awk -v dt="$1" -v s="$2" 'BEGIN { printf "%.6fs", dt * s * 1e-6 }')
    order=$([ $((r % 2)) -eq 0 ] && echo "old new" || echo "new old")
    for w in $order; do
      for k in imp exp; do run $w $k $n "$dur"; run $w $k $n 0; done
    done
  done
  r=$((r + 1))
done
median() { sort -g "$1" | awk '{ a[NR] = $1 } END { print NR % 2 ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2 }'; }
cost() { # cost WHO KIND N: us of CPU per step
  awk -v t="$(median "$tmp/cpu/$1.$2.$3")" -v z="$(median "$tmp/cpu/$1.$2.$3.0")" -v s="$(cut -d' ' -f2 "$tmp/run.$3")" \
    'BEGIN { printf "%.2f", 1e6 * (t - z) / s }'
}
echo "CPU: $(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -1), $(nproc) logical CPUs, load average $(cut -d' ' -f1-3 /proc/loadavg); $(date +%F); old $(git -C "$root" rev-parse --short "$old"), new $(git -C "$root" rev-parse --short HEAD)$(git -C "$root" diff --quiet HEAD -- runtime || echo ' (modified)'); $rounds rounds, medians of CPU us per step"
echo
echo "| n | dt (us) | steps | old implicit | old explicit | old ratio | new implicit | new explicit | new ratio | <= 1.5 | new implicit output vs old |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for n in $sizes; do
  set -- $(cat "$tmp/run.$n")
  oi=$(cost old imp $n) oe=$(cost old exp $n) ni=$(cost new imp $n) ne=$(cost new exp $n)
  moved=$(/usr/bin/python3 "$root/scripts/compare_h5.py" --except restart "$tmp/out.old.imp.$n.h5" "$tmp/out.new.imp.$n.h5" 2>&1 | tail -1 | sed 's/|/\\|/g' || true)
  awk -v n=$n -v dt="$1" -v s="$2" -v oi=$oi -v oe=$oe -v ni=$ni -v ne=$ne -v mv="$moved" 'BEGIN {
    printf "| %d | %s | %d | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %s | %s |\n", n, dt, s, oi, oe, oi / oe, ni, ne, ni / ne, ni / ne <= 1.5 ? "yes" : "no", mv }'
done
