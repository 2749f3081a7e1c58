#!/bin/sh
# bench_elbow.sh — validation 6 of issue 4 and its wall times: the elbow
# flexion (examples/elbow_flexion.sinew, 0.5 s) at the reference's dt = 50 ns
# (Zhang et al. 2019, Suppl. Table 5) and at the stable-dt estimate the
# compiler reports, their elbow angles compared frame by frame; then the same
# scene with rigid bones.  Writes the section "Elbow flexion" of
# docs/benchmarks.md (replacing an older one) and prints it.
# Usage: bench/bench_elbow.sh [DURATION]   (default 0.5s)
set -e
DUR=${1:-0.5s}
OUT=build/bench/elbow
mkdir -p $OUT
./bin/sinewc examples/elbow_flexion.sinew -o $OUT/flexion
STABLE=$($OUT/flexion --info | sed -n 's/.*stable estimate \([0-9.e+-]*\) \([a-z]*\)).*/\1\2/p')
wall() { # label dt -> runs and prints seconds of wall time
  s=$(date +%s.%N)
  $OUT/flexion --quiet --duration $DUR --dt "$2" --out $OUT/$1.h5
  e=$(date +%s.%N)
  echo "$e - $s" | bc
}
T50=$(wall dt50ns 50ns)
TST=$(wall stable "$STABLE")
REPORT=$(/usr/bin/python3 scripts/elbow_compare.py $OUT/dt50ns.h5 $OUT/stable.h5 "$T50" "$TST" "$STABLE" "$DUR")
echo "$REPORT"
/usr/bin/python3 scripts/put_section.py docs/benchmarks.md "Elbow flexion (issue 4, validation 6)" "$REPORT"
