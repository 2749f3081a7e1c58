#!/bin/sh
# test_portable.sh — sinewc builds simulators for this machine's CPU by
# default and for any x86-64 with --portable (issue 10):
#   - both build and run the pendulum, and their trajectories are bitwise
#     equal (ISO C mode: no contraction into FMA, and the vector loops keep
#     the scalar bits), every dataset but the energy diagnostic, whose work
#     sum follows the vector width, and the checkpoint /restart, which holds
#     that sum's partial sums among the step's scratch;
#   - on a CPU with AVX-512 the default simulator uses it (zmm registers) and
#     the portable one does not;
#   - --portable without libsinewrt-portable.a is a clear error (exit 4).
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
SC=$ROOT/bin/sinewc   # the optimised build: both libraries sit next to it
TMP=$(mktemp -d "${TMPDIR:-/tmp}/sinew-portable.XXXXXX") || exit 1
trap 'rm -rf "$TMP"' EXIT INT TERM

"$SC" examples/pendulum.sinew -o "$TMP/native" 2>"$TMP/err"; ok $? "sinewc (native) builds the pendulum"
"$SC" --portable examples/pendulum.sinew -o "$TMP/portable" 2>>"$TMP/err"; ok $? "sinewc --portable builds the pendulum"
diag <"$TMP/err"
"$TMP/native" --quiet --duration 2ms --out "$TMP/n.h5" >/dev/null 2>&1; ok $? "native simulator runs"
"$TMP/portable" --quiet --duration 2ms --out "$TMP/p.h5" >/dev/null 2>&1; ok $? "portable simulator runs"
out=$(/usr/bin/python3 scripts/compare_h5.py "$TMP/n.h5" "$TMP/p.h5" --except diagnostics/energy \
  --except restart/ 2>&1)
ok $? "native and portable outputs are bitwise equal (but the energy diagnostic and the checkpoint)"
echo "$out" | diag

if grep -qw avx512f /proc/cpuinfo; then
  zn=$(objdump -d "$TMP/native" | grep -c zmm)
  zp=$(objdump -d "$TMP/portable" | grep -c zmm)
  echo "# zmm instructions: native $zn, portable $zp"
  [ "$zn" -gt 0 ] && [ "$zp" -eq 0 ]; ok $? "native uses AVX-512, portable does not"
fi

mkdir -p "$TMP/rt"
cp runtime/include/*.h build/libsinewrt.a "$TMP/rt/"
SINEW_RUNTIME="$TMP/rt" "$SC" --portable examples/pendulum.sinew -o "$TMP/x" 2>"$TMP/err"
rc=$?
[ $rc -eq 4 ] && grep -q "libsinewrt-portable.a" "$TMP/err"; ok $? "--portable without its library: exit 4 naming it (got $rc)"
diag <"$TMP/err"
done_testing
