#!/bin/sh
# compare_outputs.sh OLD_SINEWC NEW_SINEWC [steps [MODEL.sinew...]] — run
# every example scene (or the models named) built by two compilers for the
# same number of steps and say how their HDF5 outputs differ
# (scripts/compare_h5.py): "bitwise", or the largest relative difference.
# Used to show what a change of the runtime does to results; a model that is
# not a runnable scene (a library) is reported as not compiling.
set -u
old=$1 new=$2 steps=${3:-2000}
[ $# -gt 3 ] && shift 3 || set -- examples/*.sinew
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
fail=0
for f in "$@"; do
  name=$(basename "$f" .sinew)
  "$old" "$f" -o "$dir/old" 2>/dev/null && "$new" "$f" -o "$dir/new" 2>/dev/null || {
    echo "$name: does not compile"; fail=1; continue; }
  # the dt the scene uses (its own, or half the stable estimate), from --info
  dt=$("$dir/new" --info 2>/dev/null | awk '/^dt:/ {
    s = $3 == "ns" ? 1e-9 : $3 == "us" ? 1e-6 : $3 == "ms" ? 1e-3 : 1; printf "%.17g", $2 * s; exit }')
  dur=$(awk -v dt="$dt" -v n="$steps" 'BEGIN { printf "%.17g", dt * n }')
  "$dir/old" --quiet --duration "$dur" --every "$dur" --out "$dir/old.h5" >/dev/null 2>&1
  "$dir/new" --quiet --duration "$dur" --every "$dur" --out "$dir/new.h5" >/dev/null 2>&1
  printf '%s (%s steps of %s s): ' "$name" "$steps" "$dt"
  /usr/bin/python3 "$(dirname "$0")/../scripts/compare_h5.py" "$dir/old.h5" "$dir/new.h5" || fail=1
done
exit $fail
