#!/bin/sh
# test_feather.sh — examples/feather_resolved.sinew (issue 32): one feather
# of the pigeon wing flapped at its root, kinematic (as the wing model) and
# fully resolved (its 192 barbs on fixed joints to an implicit rachis of 230
# elements).  Checks, from the model as written:
#   the resolved feather's joints are all in the joints' system, and its
#   rachis with its barbs is one group solved in the rachis' band
#   (docs/physics.md, "The band path");
#   so the stable estimate is a barb's own (no joint, no rachis element):
#   `--info` says "set by rod";
#   2 ms at 1 us run, and each rachis' root element turns as its
#   angular_velocity prescribes, theta(t) = 20 deg (1 - cos 2 pi f t) with
#   f = 2.63 Hz (the held node and the turned element of a rod in a band
#   group, and of an explicit one): within 1e-12 rad of the closed form.
# The comparison of the two feathers over a stroke is in docs/validation.md
# ("One feather, kinematic and resolved"); a run takes 100 s of CPU.
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
scratch feather
"$SINEWC" examples/feather_resolved.sinew -o "$TMP/fr" 2>"$TMP/err"; ok $? "the two feathers compile"
diag <"$TMP/err"
"$TMP/fr" --info >"$TMP/info" 2>&1; ok $? "--info"
grep -q "192 of 192 joints" "$TMP/info"; ok $? "the resolved feather's 192 joints are implicit"
grep -q "1 of them an implicit rod and its leaves, solved in its band" "$TMP/info"
ok $? "its rachis and barbs are one group, solved in the rachis' band"
grep -A1 '^dt:' "$TMP/info" | diag
grep -A1 '^dt:' "$TMP/info" | grep -q '  set by rod '; ok $? "the step's estimate is a rod's (a barb's), not a joint's"
(cd "$TMP" && ./fr --duration 2ms --dt 1us --every 0.5ms --out fr.h5 --quiet) 2>"$TMP/err"
ok $? "it runs 2 ms at 1 us"
diag <"$TMP/err"
/usr/bin/python3 - "$TMP/fr.h5" >"$TMP/py" 2>&1 <<'PY'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
t = f["time"][:]
worst = 0.0
for rod in ("rk", "rr"):
    P = f["/rods/%s/position" % rod][:]
    D = f["/rods/%s/directors" % rod][:]
    for i in range(len(t)):
        theta = np.radians(20) * (1 - np.cos(2 * np.pi * 2.63 * t[i]))
        d3 = D[i][0][2]             # the root element's tangent
        got = np.arctan2(-d3[2], d3[0])
        worst = max(worst, abs(got - theta), np.linalg.norm(P[i][0] - P[0][0]))
print("root element's turn against 20 deg (1 - cos 2 pi f t), and the root node's drift, over %d frames: largest error %.3g" % (len(t), worst))
sys.exit(0 if worst < 1e-12 else 1)
PY
rc=$?
diag <"$TMP/py"
ok $rc "each rachis' root turns as prescribed and stays in place (1e-12)"
done_testing
