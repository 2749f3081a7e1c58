#!/bin/sh
# plots.sh — `make plots`: the figures of docs/img/ from whatever outputs exist.
#
#   docs/img/force_length.png    build/validation/force_length_held.txt
#                                (points eta, F/F_max: test_muscle, length
#                                held) on the reference curve
#   docs/img/force_length_load.png  build/validation/force_length_load.txt
#                                (test_muscle, F_set prescribed)
#   docs/img/force_velocity.png  build/validation/force_velocity.txt
#                                (points u in l0/s, F/F_qs) on Hill's curve
#   docs/img/elbow_angle.png     build/bench/elbow/{dt50ns,stable}.h5 (make
#                                bench), else build/demo/elbow_flexion.h5
#                                (make demo), joint `arm.elbow`
#   docs/img/elbow_frame.png     build/demo/elbow_flexion.h5: the rods at
#                                t = 0.3 s (`sinew-plot frames --every 100`
#                                of its frames every 1 ms, the fourth)
#   docs/img/am_free.png         build/am_free/rate{1,0.5,0.25}.h5, runs of
#                                examples/am_free.sinew (scripts/am_free.py
#                                --run makes them)
#
# `make test` writes the tables, `make bench` or `make demo` the runs; a
# missing input is skipped with a line saying which file was missing.  A
# sinew-plot failure on an input that exists is an error (exit 1).
cd "$(dirname "$0")/.." || exit 1
PLOT=scripts/sinew-plot
made=0 skipped=0 failed=0

# the first of the arguments that exists, else the first
first_of() {
  for f in "$@"; do [ -e "$f" ] && { echo "$f"; return; }; done
  echo "$1"
}

# draw OUT INPUT ARGS...: run sinew-plot ARGS -o OUT if INPUT exists
draw() {
  out=$1 input=$2; shift 2
  if [ ! -e "$input" ]; then
    echo "plots: skipped $out: $input not found (not produced yet)"
    skipped=$((skipped + 1))
  elif "$PLOT" "$@" -o "$out"; then
    echo "plots: wrote $out from $input"
    made=$((made + 1))
  else
    echo "plots: FAILED $out from $input" >&2
    failed=$((failed + 1))
  fi
}

mkdir -p docs/img
fl=build/validation/force_length_held.txt
fll=build/validation/force_length_load.txt
fv=build/validation/force_velocity.txt
draw docs/img/force_length.png "$fl" force-length --points "$fl"
draw docs/img/force_length_load.png "$fll" force-length --points "$fll"
draw docs/img/force_velocity.png "$fv" force-velocity --points "$fv"
if [ -e build/bench/elbow/stable.h5 ]; then
  draw docs/img/elbow_angle.png build/bench/elbow/dt50ns.h5 angle build/bench/elbow/dt50ns.h5 \
    build/bench/elbow/stable.h5 --joint arm.elbow --label "dt = 50 ns" --label "stable dt"
else
  h5=build/demo/elbow_flexion.h5
  draw docs/img/elbow_angle.png "$h5" angle "$h5" --joint arm.elbow
fi

h5=build/demo/elbow_flexion.h5
if [ ! -e "$h5" ]; then
  echo "plots: skipped docs/img/elbow_frame.png: $h5 not found (not produced yet)"
  skipped=$((skipped + 1))
elif "$PLOT" frames "$h5" -o build/demo/frames --every 100 --view 10,-75 &&
  cp build/demo/frames/frame_00003.png docs/img/elbow_frame.png; then
  echo "plots: wrote docs/img/elbow_frame.png from $h5"
  made=$((made + 1))
else
  echo "plots: FAILED docs/img/elbow_frame.png from $h5" >&2
  failed=$((failed + 1))
fi

am=build/am_free/rate0.25.h5
if [ ! -e "$am" ]; then
  echo "plots: skipped docs/img/am_free.png: $am not found (scripts/am_free.py --run makes it)"
  skipped=$((skipped + 1))
elif /usr/bin/python3 scripts/am_free.py --plot docs/img/am_free.png >/dev/null; then
  echo "plots: wrote docs/img/am_free.png from build/am_free/"
  made=$((made + 1))
else
  echo "plots: FAILED docs/img/am_free.png from build/am_free/" >&2
  failed=$((failed + 1))
fi

echo "plots: $made written, $skipped skipped, $failed failed"
[ "$failed" -eq 0 ]
