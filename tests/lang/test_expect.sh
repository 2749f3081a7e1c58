#!/bin/sh
# test_expect.sh — expect statements, a model as its own golden test:
#
#   examples/pendulum.sinew carries three expectations from the physical
#   pendulum's closed forms (the angle half a period after release, the
#   swing never passing it, the pivot's reaction at rest there); its
#   simulator checks them over 1.2 s and exits 0, reporting each with the
#   value it saw;
#   the same pendulum held to wrong bounds exits 5 and names the failing
#   expectation, its file:line, the value and the bounds; --quiet keeps the
#   failures only; the HDF5 file is complete and says an expectation failed;
#   a run cut short (--duration) lists what it did not reach and exits 0,
#   but a window already left before the end is a failure;
#   expectations inside a component read the instance's own joint; and the
#   generated C carries each expectation with a #line back to it.
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
SC=$SINEWC_CHECK
scratch expect

"$SC" examples/pendulum.sinew -o "$TMP/pendulum" 2>"$TMP/err"; ok $? "the pendulum compiles"
diag <"$TMP/err"
"$TMP/pendulum" --duration 1.2s --out "$TMP/p.h5" 2>"$TMP/run"; rc=$?
ok $((rc != 0)) "its expectations hold over 1.2 s (exit $rc)"
diag <"$TMP/run"
n=$(grep -c '^pendulum: passed: expect ' "$TMP/run")
ok $((n != 3)) "each of the three is reported passed ($n)"
grep -q '^pendulum: passed: expect angle(pivot) at 0.581 s within 0.05 deg of 20 deg;  # pendulum.sinew:' "$TMP/run"
ok $? "a report line quotes the statement and its file:line"
grep -Eq '^    value 19\.99[0-9]* deg, expected in \[19\.95 deg, 20\.05 deg\]$' "$TMP/run"
ok $? "the value is shown in the unit the bounds were written in"
grep -q '^pendulum: expectations: 3 passed, 0 failed$' "$TMP/run"; ok $? "and a summary line"

# the same model held to bounds it does not meet
sed 's/within 0.05 deg of 20 deg;/within 0.05 deg of 25 deg;/; s/in (-0.05 deg, 20.05 deg);/in (-0.05 deg, 15 deg);/' \
  examples/pendulum.sinew >"$TMP/wrong.sinew"
"$SC" "$TMP/wrong.sinew" -o "$TMP/wrong" 2>"$TMP/err"; ok $? "a pendulum with wrong expectations compiles"
"$TMP/wrong" --duration 1.2s --out "$TMP/w.h5" 2>"$TMP/run"; rc=$?
ok $((rc != 5)) "a failed expectation exits 5 (exit $rc)"
diag <"$TMP/run"
grep -q '^wrong: FAILED: expect angle(pivot) at 0.581 s within 0.05 deg of 25 deg;  # wrong.sinew:' "$TMP/run"
ok $? "the failure names the statement"
grep -Eq '^    value 19\.99[0-9]* deg, expected in \[24\.95 deg, 25\.05 deg\]$' "$TMP/run"
ok $? "with the value and the bounds"
grep -Eq '^    from -?[0-9.e+-]+ deg to 19\.99[0-9]* deg over 664801 steps, expected in \[-0\.05 deg, 15 deg\]$' "$TMP/run"
ok $? "a window reports the range it saw over its steps"
grep -q '^wrong: expectations: 1 passed, 2 failed$' "$TMP/run"; ok $? "the summary counts them"
/usr/bin/python3 - "$TMP/w.h5" <<'PY' 2>&1 | diag
import sys, h5py
with h5py.File(sys.argv[1]) as f:
    status, frames = f.attrs["status"], f["/time"].shape[0]
    status = status.decode() if isinstance(status, bytes) else status
    assert status == "complete; 2 expectations failed", status
    assert frames == 1201, frames
PY
ok $? "the file is complete (1201 frames) and its status says 2 expectations failed"
"$TMP/wrong" --duration 1.2s --out "$TMP/w.h5" --quiet 2>"$TMP/run"; rc=$?
n=$(grep -c '' "$TMP/run")
ok $((rc != 5 || n != 5)) "--quiet keeps the two failures and the summary (exit $rc, $n lines)"

# a run cut short
"$TMP/pendulum" --duration 0.1s --out "$TMP/p.h5" 2>"$TMP/run"; rc=$?
ok $rc "a run that ends before the expectations' times exits 0"
grep -q '^pendulum: expectations: 0 passed, 0 failed, 3 not reached$' "$TMP/run"
ok $? "and lists them as not reached"
grep -q '^    the run ended before t = 1.2 s, within the window$' "$TMP/run"
ok $? "a window it entered is not reached either"
"$TMP/wrong" --duration 0.5s --out "$TMP/w.h5" 2>"$TMP/run"; rc=$?
ok $((rc != 5)) "a window already left before the run ends is a failure (exit $rc)"
diag <"$TMP/run"

# inside a component: the instance's own joint
cat >"$TMP/pair.sinew" <<'MODEL'
material bone { E = 15 GPa; density = 1750 kg/m^3; }
component bar(x = 0 m) {
  rod r { material = bone; start = (x, 0 m, 0 m); direction = (0, 0, -1); normal = (1, 0, 0);
          length = 0.5 m; radius = 1 cm; elements = 10; }
  joint pin = hinge(r.start, (x, 0 m, 0 m)) { axis = (0, 1, 0); }
  expect angle(pin) over (0 s, 1 ms) within 1e-6 deg of 0 deg;
}
use left = bar();
use right = bar(x = 1 m);
gravity (0, 0, -9.81) m/s^2;
simulate { duration = 1 ms; }
output "pair.h5";
MODEL
"$SC" "$TMP/pair.sinew" --emit-c -o "$TMP/pair.c" 2>"$TMP/err"; ok $? "expectations in a component compile"
diag <"$TMP/err"
n=$(grep -c 'expect.quantity = SW_EXPECT_JOINT_ANGLE;' "$TMP/pair.c")
i0=$(grep -Fc 'expect.index = joint_id[0];' "$TMP/pair.c"); i1=$(grep -Fc 'expect.index = joint_id[1];' "$TMP/pair.c")
ok $((n != 2 || i0 != 1 || i1 != 1)) "one per instance, each on its own joint ($n; $i0, $i1)"
n=$(grep -A3 '^#line 6 "' "$TMP/pair.c" | grep -c '^    swExpectDesc expect;$')
ok $((n != 2)) "the C of each has a #line to the statement ($n)"
"$SC" "$TMP/pair.sinew" -o "$TMP/pair" 2>"$TMP/err" && "$TMP/pair" --out "$TMP/pair.h5" --quiet 2>"$TMP/run"
ok $? "a hanging bar keeps its angle (both instances pass)"
diag <"$TMP/run"

done_testing
