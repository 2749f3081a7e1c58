#!/bin/sh
# test_joint_limits.sh — a hinge with an angle range, from the language to
# the file:
#
#   a rod level on an anchored hinge (axis y) with range = (-20 deg, 30 deg)
#   falls under gravity onto its upper limit and rests there, damped; the
#   file has /joints/pivot/limit_torque in N m and the limits as attributes
#   of the group (angle_min, angle_max in rad, with their _units); the angle
#   never passes 30 deg by more than the penalty's give, and at rest the
#   limit's couple is the gravity moment M g (L/2) cos(theta) (1e-3) and the
#   overshoot theta - 30 deg is that couple over limit_stiffness (1e-3).
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
SC=$SINEWC_CHECK
PY=/usr/bin/python3
scratch jlimits

cat >"$TMP/limit.sinew" <<'EOF2'
# a level rod on a hinge, falling onto its upper limit
material steel { E = 200 GPa; density = 7800 kg/m^3; }
rod arm { material = steel; start = (0, 0, 0) m; direction = (1, 0, 0); normal = (0, 0, 1);
          length = 0.5 m; radius = 1 cm; elements = 4; rigid = true; damping = 2 kg/m/s; }
joint pivot = hinge(arm.start, (0, 0, 0) m) {
  axis = (0, 1, 0);
  range = (-20 deg, 30 deg);
  limit_stiffness = 100 N m/rad;
  limit_damping = 5 N m s/rad;
}
gravity (0, 0, -9.81) m/s^2;
simulate { duration = 2 s; }
output "limit.h5" every 10 ms;
EOF2
"$SC" "$TMP/limit.sinew" -o "$TMP/limit" 2>"$TMP/err"; ok $? "a limited hinge compiles"
diag <"$TMP/err"
(cd "$TMP" && ./limit --quiet) 2>"$TMP/err"; ok $? "it runs"
diag <"$TMP/err"
$PY - "$TMP/limit.h5" >"$TMP/out" 2>&1 <<'EOF2'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
fails = 0
def check(cond, what):
    global fails
    print(("ok   " if cond else "FAIL ") + what)
    fails += 0 if cond else 1
j = f["joints/pivot"]
check("limit_torque" in j and j["limit_torque"].shape[1:] == (3,), "limit_torque [F, 3]")
check(j["limit_torque"].attrs["units"] in ("N m", b"N m"), "limit_torque in N m")
lo, hi = j.attrs["angle_min"], j.attrs["angle_max"]
check(abs(lo + np.radians(20)) < 1e-15 and abs(hi - np.radians(30)) < 1e-15,
      "angle_min %.6g, angle_max %.6g rad" % (lo, hi))
check(j.attrs["angle_max_units"] in ("rad", b"rad"), "angle_max_units rad")
check(j.attrs["limit_stiffness"] == 100.0, "limit_stiffness %g" % j.attrs["limit_stiffness"])
a = j["angle"][:]
M, g, L, k = 7800 * np.pi * 0.01 ** 2 * 0.5, 9.81, 0.5, 100.0
theta = a[-1]
tau = M * g * L / 2 * np.cos(theta)
over = a.max() - hi
print("# largest angle %.6f rad (limit %.6f), rest %.9f rad, overshoot %.6g rad, "
      "tau / k %.6g rad" % (a.max(), hi, theta, theta - hi, tau / k))
check(over < 0.1, "the angle is held: at most %.4f rad past the limit" % over)
C = j["limit_torque"][-1]
check(abs(-C[1] - tau) <= 1e-3 * tau, "limit couple %.6g N m vs M g L/2 cos(theta) %.6g" % (-C[1], tau))
check(abs((theta - hi) - tau / k) <= 1e-3 * tau / k,
      "overshoot %.6g rad vs tau / k_l %.6g rad" % (theta - hi, tau / k))
sys.exit(1 if fails else 0)
EOF2
ok $? "the file holds the limit's couple and the angle held"
diag <"$TMP/out"
done_testing
