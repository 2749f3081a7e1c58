#!/bin/sh
# test_wing.sh — models/pigeon_wing.sinew, the feathered wing (Zhang et al.
# 2019, Suppl. Notes 5 and 7.4) in the reference's kinematic form: it checks
# with the reference code's counts (6 bones, 19 rachises, 3144 barbs: GitHub
# mattialab/elastica, source/Wing.cpp), compiles (build() unoptimised: the
# C compiler's time), runs a few steps, and its layout at t = 0 has the
# reference code's joint angles (its own first output: shoulder antero-
# posterior -38.659808254090095 deg, elbow 62.650124219930149 deg); and
# the fully resolved wing compiles and runs a few steps at its step.
. "$(dirname "$0")/tap.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export SINEW_PATH="$ROOT/models"

"$SINEWC_ASAN" --check "$ROOT/models/pigeon_wing.sinew" 2>"$tmp/check"; ok $? "the wing checks"
diag <"$tmp/check"
grep -q 'ok: 2 files, 3173 rods (12823 elements), 4 muscles (4 filaments), 3170 joints' "$tmp/check"
ok $? "3169 rods of the reference's wing and 4 muscle anchors; 7 joints and 3163 kinematic ones"
start=$(date +%s)
"$SINEWC" "$ROOT/models/pigeon_wing.sinew" -o "$tmp/wing" 2>"$tmp/err"; ok $? "it compiles"
diag <"$tmp/err"
echo "# sinewc and cc took $(($(date +%s) - start)) s"
# its numbers against Suppl. Tables 1, 2 and 10 (tests/reference/tables.tsv;
# tests/lang/test_tables.sh checks the other scenes' the same way)
"$tmp/wing" --info >"$tmp/pigeon_wing.info" 2>"$tmp/err" || diag <"$tmp/err"
/usr/bin/python3 "$ROOT/tests/lang/tables_check.py" "$ROOT/tests/reference/tables.tsv" "$tmp" "$ROOT" \
  pigeon_wing >"$tmp/tables" 2>&1
rc=$?
sed 's/^ok - /# checked: /' "$tmp/tables"
ok $rc "its $(grep -c '^ok - ' "$tmp/tables") rows of the reference's tables hold (tables.tsv: checked or documented deviations)"
(cd "$tmp" && ./wing --quiet --duration 20us --every 10us --out "$tmp/wing.h5") 2>"$tmp/err"
ok $? "it runs 20 us (37 steps)"
diag <"$tmp/err"
/usr/bin/python3 - "$tmp/wing.h5" <<'PY'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
H = f["/rods/humerus/position"][0]
d3h = f["/rods/humerus/directors"][0][-1][2]
d3r = f["/rods/radius/directors"][0][0][2]
ap = np.degrees(np.arctan(-H[-1][0] / abs(H[-1][1])))
el = 90 - np.degrees(np.arccos(np.dot(d3h, d3r)))
print("# at t = 0: shoulder antero-posterior %.12f deg, elbow %.12f deg" % (ap, el))
ok = abs(ap + 38.659808254090095) < 1e-9 and abs(el - 62.650124219930149) < 1e-9
sys.exit(0 if ok and np.all(np.isfinite(f["/rods/humerus/position"][:])) else 1)
PY
ok $? "its layout has the reference code's shoulder and elbow angles at t = 0 (within 1e-9 deg)"
# the fully resolved wing (every barb and rachis on an ordinary fixed
# joint) at its 1 us: its digits carry two feathers' roots on their last
# element, whose two ports the runtime once condensed into a singular
# system (the digits turned away within 16 steps; test_joint_alias)
"$SINEWC" "$ROOT/models/pigeon_wing_resolved.sinew" -o "$tmp/resolved" 2>"$tmp/err"
ok $? "the resolved wing compiles"
diag <"$tmp/err"
(cd "$tmp" && ./resolved --quiet --duration 60us --every 20us --out "$tmp/resolved.h5") 2>"$tmp/err"
ok $? "the resolved wing runs 60 steps of 1 us"
diag <"$tmp/err"
done_testing
