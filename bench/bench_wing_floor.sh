#!/bin/sh
# bench_wing_floor.sh [ROUNDS] [DURATION] — what the kinematic wing's step
# costs against the part of it no joint, drag or bookkeeping can remove: its
# barbs' own rod step.  Two simulators from this tree, one thread each, run
# interleaved ROUNDS times (default 5; the order alternates), each for
# DURATION (default 5 ms) at the wing's step of 1 us, less a 0 s run of the
# same simulator (start-up):
#   wing   models/pigeon_wing.sinew as it is;
#   barbs  3150 free rods of 4 elements, the wing's barbs' count, element
#          count, material, radius and damping, lengths 11.4 to 114 mm as
#          the wing's (50 rows of 63); no joint, drag, muscle or gravity, nothing written
#          but the energy (the scene is generated here).
# Prints the medians of wall time per step, each scaled to the whole stroke
# (0.51 s, 510,000 steps), and the stroke's two-minute budget per step.  The
# barbs' figure is a floor for one core at the model's step: on one thread
# the wing cannot cost less than its barbs' elastic step.  Run it on an
# otherwise idle machine.
set -eu
rounds=${1:-5} dur=${2:-5ms}
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
. bench/bench_base.sh
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cat > "$tmp/barbs.sinew" <<'EOF'
# the wing's 3150 barbs alone (bench/bench_wing_floor.sh): models/pigeon_wing.sinew's
# keratin, radius, elements and damping, free, at the wing's step
material keratin { E = 2.5 MPa; G = 2 / 3 * 2.5 MPa; density = 2.5 kg/m^3; }
for row[i] in (0, 49) {
  for barb[j] in (0, 62) {
    rod r { material = keratin; start = (2 mm * j, 2 mm * i, 0 mm); direction = (0, 1, 0.1); normal = (0, 0, 1);
            length = 11.4 mm + 1.6 mm * j; radius = 1.5 mm; elements = 4; damping = 0.005 kg/m/s; }
  }
}
simulate { dt = 1 us; duration = 5 ms; }
output "barbs.h5" every 5 ms { positions row[0].barb[0].r; energy; }
EOF
SINEW_PATH="$root/models" bin/sinewc models/pigeon_wing.sinew -o "$tmp/wing" > /dev/null
bin/sinewc "$tmp/barbs.sinew" -o "$tmp/barbs" > /dev/null
wall() { # wall BIN DURATION: the run's wall seconds, one thread
  /usr/bin/time -f 'wall %e' -o "$tmp/time" "$tmp/$1" --quiet --threads 1 --dt 1us --duration "$2" --every "$2" \
    --out "$tmp/$1.h5" > /dev/null 2>&1 || echo "# $1 failed" >&2
  awk '$1 == "wall" { print $2 }' "$tmp/time"
}
steps=$(bench_steps "$tmp/wing" "$dur")
r=0
while [ $r -lt "$rounds" ]; do
  for w in $([ $((r % 2)) -eq 0 ] && echo wing barbs || echo barbs wing); do
    z=$(wall $w 0)
    c=$(wall $w "$dur")
    echo "$c $z" | awk -v n="$steps" '{ printf "%.6f\n", ($1 - $2) / n }' >> "$tmp/$w.t"
  done
  r=$((r + 1))
done
median() { sort -g "$1" | awk '{ w[NR] = $1 } END {
  printf "%.3f", 1e3 * (NR % 2 ? w[(NR + 1) / 2] : (w[NR / 2] + w[NR / 2 + 1]) / 2) }'; }
slots() { "$tmp/$1" --info 2>/dev/null | sed -n 's/^rods: \([0-9]*\) (\([0-9]*\) elements, \([0-9]*\) nodes).*/\1 rods, \2 elements, \3 slots/p'; }
echo "CPU: $(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -1), $(nproc) logical CPUs;" \
     "load average $(cut -d' ' -f1-3 /proc/loadavg); git $(git rev-parse --short HEAD)$(git diff --quiet HEAD -- runtime || echo ' (modified)');" \
     "$dur ($steps steps) at 1 us, $rounds rounds, one thread"
printf '%-6s %-40s %12s %16s\n' scene "" "ms/step" "0.51 s at that"
for w in wing barbs; do
  a=$(median "$tmp/$w.t")
  printf '%-6s %-40s %12s %14s s\n' $w "$(slots $w)" "$a" "$(echo "$a" | awk '{ printf "%.0f", $1 * 510 }')"
done
echo "budget for 2 minutes: $(awk 'BEGIN { printf "%.3f", 120e3 / 510000 }') ms/step (less start-up)"
