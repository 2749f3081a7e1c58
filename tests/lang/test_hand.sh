#!/bin/sh
# test_hand.sh — the tutorial's hand (examples/hand.sinew, models/finger.sinew)
# as its own golden test:
#
#   the finger file is imported into a namespace, so the scene's own
#   'material bone' does not clash with the finger's; the scene compiles and
#   runs its full 0.3 s, and its four expectations (the index's PIP resting
#   on its 100 deg limit, the ring finger's on 0 deg, no joint past a limit
#   by half a degree) pass with exit 0; the output holds what the scene's
#   output block asks for (angles of the four hinges, the two muscles'
#   forces, the two PIP limits' reaction couples, the fingertip probe) and
#   the flexor's via points; a second run compares equal to the first with
#   --compare (a golden file), and one with a weaker grip does not (exit 5).
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
scratch hand

"$SINEWC_CHECK" examples/hand.sinew -o "$TMP/hand" 2>"$TMP/err"; ok $? "the hand compiles"
diag <"$TMP/err"
"$TMP/hand" --out "$TMP/golden.h5" >"$TMP/run" 2>&1; rc=$?
ok $rc "its expectations hold over 0.3 s (exit $rc)"
grep -A1 '^hand: \(passed\|FAILED\)' "$TMP/run" | diag
grep -q '^hand: expectations: 4 passed, 0 failed$' "$TMP/run"
ok $? "all four are reported passed"

py() { /usr/bin/python3 -c "$1" "$TMP/golden.h5" 2>&1; }
out=$(py '
import sys, h5py
f = h5py.File(sys.argv[1], "r")
need = ["joints/index.mcp_joint/angle", "joints/index.pip_joint/angle",
        "joints/ring.mcp_joint/angle", "joints/ring.pip_joint/angle",
        "joints/index.pip_joint/limit_torque", "joints/ring.pip_joint/limit_torque",
        "muscles/index.flexor/force", "muscles/ring.extensor/force", "probes/fingertip"]
missing = [n for n in need if n not in f]
print("missing:", missing)
print("via points of the flexor:", f["muscles/index.flexor"].attrs["via"].reshape(-1, 3).tolist())
print("PIP limit couple at the end (N m):", f["joints/index.pip_joint/limit_torque"][-1].tolist())
sys.exit(1 if missing else 0)')
ok $? "the output holds the selected angles, forces, limit couples and the probe"
echo "$out" | diag

"$TMP/hand" --quiet --out "$TMP/again.h5" --compare "$TMP/golden.h5" >"$TMP/cmp" 2>&1; rc=$?
ok $rc "a second run equals the first (--compare, exit $rc)"
diag <"$TMP/cmp"
"$TMP/hand" --quiet --set grip=0.03 --out "$TMP/weak.h5" --compare "$TMP/golden.h5" >"$TMP/cmp2" 2>&1; rc=$?
ok $((rc != 5)) "a weaker grip differs from the golden file (exit $rc, expected 5)"
grep -v "^ *FAILED /joints/.*.f0" "$TMP/cmp2" | head -6 | diag
done_testing
