#!/bin/sh
# bench_stiff.sh — the stiff-capable scheme (integrator = imex) against the
# explicit one on the two targets of issue 11, written as the section
# "Stiff scenes (issue 11)" of docs/benchmarks.md (replacing an older one):
#   1. examples/elbow_flexion.sinew, 0.5 s: the elbow angle against the run
#      at the reference's dt = 50 ns, for position Verlet at its stable
#      estimate, imex at its estimate, and imex with the bones held rigid
#      (sinewc --let rigid_bones=true) at its estimate;
#   2. examples/bone_chain.sinew (joints of k = 5e9 N/m), DURATION_CHAIN:
#      the tip of the chain and the base hinge's angle against the explicit
#      run at 0.9 of its stable estimate, for imex with rigid bones at 100x
#      and 1000x that step.
# Each fast run is repeated REPEAT times, interleaved, and the median wall
# time is quoted; the slow references run once.
# Usage: bench/bench_stiff.sh [DURATION_ELBOW] [DURATION_CHAIN] [REPEAT]
set -e
DUR=${1:-0.5s}
DURC=${2:-10ms}
REPEAT=${3:-3}
OUT=build/bench/stiff
mkdir -p $OUT
./bin/sinewc examples/elbow_flexion.sinew -o $OUT/elbow
./bin/sinewc examples/elbow_flexion.sinew -o $OUT/elbow_rigid --let rigid_bones=true
./bin/sinewc examples/bone_chain.sinew -o $OUT/chain
./bin/sinewc examples/bone_chain.sinew -o $OUT/chain_rigid --let rigid_bones=true

estimate() { # SIM [options] -> the stable estimate --info reports, as "1.2us",
  # less 1e-5 of it: --info rounds it to 6 digits, which may round it up
  "$@" --info | sed -n 's/.*stable estimate \([0-9.e+-]*\) \([a-z]*\)).*/\1 \2/p' |
    { read -r v u; printf '%.6g%s\n' "$(echo "$v * 0.99999" | bc -l)" "$u"; }
}
wall() { # OUT.h5 SIM [options] -> seconds of wall time
  o=$1; shift
  s=$(date +%s.%N)
  "$@" --quiet --out "$o" || true   # an unstable run is a result too
  e=$(date +%s.%N)
  echo "$e - $s" | bc
}

# 1. the elbow
REF=$OUT/elbow_50ns.h5
# bench_elbow.sh's 50 ns run of the same scene, if make bench just made it
if [ ! -s $REF ] && [ "$DUR" = 0.5s ] && [ -s build/bench/elbow/dt50ns.h5 ]; then
  cp build/bench/elbow/dt50ns.h5 $REF
  echo nan > $OUT/elbow_50ns.wall
fi
[ -s $REF ] || wall $REF $OUT/elbow --duration $DUR --dt 50ns > $OUT/elbow_50ns.wall
E_V=$(estimate $OUT/elbow)
E_I=$(estimate $OUT/elbow --integrator imex)
E_R=$(estimate $OUT/elbow_rigid --integrator imex)
: > $OUT/elbow.walls
for k in $(seq $REPEAT); do
  echo "verlet $(wall $OUT/elbow_verlet.h5 $OUT/elbow --duration $DUR --dt $E_V)" >> $OUT/elbow.walls
  echo "imex $(wall $OUT/elbow_imex.h5 $OUT/elbow --duration $DUR --dt $E_I --integrator imex)" >> $OUT/elbow.walls
  echo "rigid $(wall $OUT/elbow_rigid.h5 $OUT/elbow_rigid --duration $DUR --dt $E_R --integrator imex)" >> $OUT/elbow.walls
done

# 2. the bone chain
E_C=$(estimate $OUT/chain)
FINE=$(echo "$E_C" | sed 's/[a-z]*$//')
UNIT=$(echo "$E_C" | sed 's/^[0-9.e+-]*//')
times() { printf '%.6g%s' "$(echo "$1 * $FINE" | bc -l)" "$UNIT"; } # FACTOR -> a dt
DT_FINE=$(times 0.9)
DT_100=$(times 90)
DT_1000=$(times 900)
CREF=$OUT/chain_fine.h5
wall $CREF $OUT/chain --duration $DURC --dt $DT_FINE --every 0.1ms > $OUT/chain_fine.wall
: > $OUT/chain.walls
for k in $(seq $REPEAT); do
  echo "x100 $(wall $OUT/chain_100.h5 $OUT/chain_rigid --integrator imex --duration $DURC --dt $DT_100 --every 0.1ms)" >> $OUT/chain.walls
  echo "x1000 $(wall $OUT/chain_1000.h5 $OUT/chain_rigid --integrator imex --duration $DURC --dt $DT_1000 --every 0.1ms)" >> $OUT/chain.walls
done

REPORT=$(/usr/bin/python3 scripts/stiff_report.py $OUT "$DUR" "$DURC" "$E_V" "$E_I" "$E_R" "$E_C" \
         "$DT_FINE" "$DT_100" "$DT_1000")
echo "$REPORT"
/usr/bin/python3 scripts/put_section.py docs/benchmarks.md "Stiff scenes (issue 11)" "$REPORT"
