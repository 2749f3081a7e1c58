#!/bin/sh
# plots.sh — `make plots`: the figures of docs/img/ from whatever outputs exist.
#
#   docs/img/force_length.png    build/validation/force_length.{csv,txt}
#                                (points eta, F/F_max) on the reference curve
#   docs/img/force_velocity.png  build/validation/force_velocity.{csv,txt}
#                                (points u in l0/s, F/F_qs) on Hill's curve
#   docs/img/elbow_angle.png     build/examples/elbow_flexion.h5, joint `elbow`
#
# The runs that write these inputs are not wired yet; a missing input is
# skipped with a line saying which file was missing, not an error.  A
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
fl=$(first_of build/validation/force_length.csv build/validation/force_length.txt)
fv=$(first_of build/validation/force_velocity.csv build/validation/force_velocity.txt)
draw docs/img/force_length.png "$fl" force-length --points "$fl"
draw docs/img/force_velocity.png "$fv" force-velocity --points "$fv"
h5=build/examples/elbow_flexion.h5
draw docs/img/elbow_angle.png "$h5" angle "$h5" --joint elbow

echo "plots: $made written, $skipped skipped, $failed failed"
[ "$failed" -eq 0 ]
