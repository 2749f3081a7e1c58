#!/bin/sh
# test_output_select.sh — output selections and a file that describes itself:
#
#   a horizontal cantilever and a hanging rod at rest under their weight,
#   with per-rod selections (curvature and internal couple of the beam,
#   strain and internal force and positions of the rope): exactly the
#   selected datasets are written, and their values are the closed forms of
#   the statics (beam: kappa = w (L - s)^2 / (2 E I), couple E I kappa; rope:
#   tension rho A g (L - s) and, under the rods' law n = EA sigma / e, axial
#   strain tau / (1 - tau) with tau = rho g (L - s) / E);
#   rod, joint and muscle groups carry kind, material, where, geometry and
#   constants, each number with NAME_units; /params is a table of name,
#   value, unit and default; joint and muscle quantities narrow to the ones
#   named (angle elbow; force biceps;).
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
SC=$SINEWC_CHECK
PY=/usr/bin/python3
scratch outsel

cat >"$TMP/statics.sinew" <<'EOF'
# A horizontal cantilever and a hanging rod at rest under their weight
param g0 = 9.81 m/s^2;
material rubber { E = 100 MPa; density = 1000 kg/m^3; }
material gel { E = 1 MPa; density = 1000 kg/m^3; }
rod beam { material = rubber; start = (0, 0, 0) m; direction = (1, 0, 0); normal = (0, 0, 1);
           length = 0.3 m; radius = 1 cm; elements = 40; damping = 5 kg/m/s; }
rod rope { material = gel; start = (1, 0, 0) m; direction = (0, 0, -1); normal = (1, 0, 0);
           length = 0.5 m; radius = 1 cm; elements = 40; damping = 5 kg/m/s; }
clamp beam.start;
clamp rope.start;
gravity (0, 0, -1) * g0;
simulate { duration = 1 s; }
output "statics.h5" every 0.1 s {
  curvature beam;
  internal_couple beam;
  strain rope;
  internal_force rope;
  positions rope;
}
EOF
"$SC" "$TMP/statics.sinew" -o "$TMP/statics" 2>"$TMP/err"; ok $? "the statics scene compiles"
diag <"$TMP/err"
(cd "$TMP" && ./statics --quiet --set g0=9.81m/s^2) 2>"$TMP/err"; ok $? "it runs"
diag <"$TMP/err"
$PY - "$TMP/statics.h5" >"$TMP/out" 2>&1 <<'EOF'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
fails = 0
def check(cond, what):
    global fails
    print(("ok   " if cond else "FAIL ") + what)
    fails += 0 if cond else 1
beam, rope = f["rods/beam"], f["rods/rope"]
check(sorted(beam) == ["curvature", "internal_couple"], "beam datasets %s" % sorted(beam))
check(sorted(rope) == ["internal_force", "node_radius", "position", "strain"], "rope datasets %s" % sorted(rope))
n, r, rho, g = 40, 0.01, 1000.0, 9.81
A, I = np.pi * r * r, np.pi * r ** 4 / 4
# beam: bending about d2 (d3 = x, d1 = z), kappa = w (L - s)^2 / (2 E I) at
# the interior nodes s = j L / n
E, L = 100e6, 0.3
s = np.arange(1, n) * L / n
kappa_ref = rho * A * g * (L - s) ** 2 / (2 * E * I)
k = beam["curvature"][-1]
err = np.max(np.abs(-k[:, 1] / kappa_ref - 1))
check(err < 1e-3, "beam curvature against w (L - s)^2 / (2 E I): largest relative error %.2e" % err)
check(np.max(np.abs(k[:, [0, 2]])) == 0.0, "no curvature about d1, no twist")
c = beam["internal_couple"][-1]
err = np.max(np.abs(-c[:, 1] / (E * I * kappa_ref) - 1))
check(err < 1e-3, "beam internal couple against E I kappa: largest relative error %.2e" % err)
# rope: at element centres s, tension and axial strain
E, L = 1e6, 0.5
s = (np.arange(n) + 0.5) * L / n
tension = rho * A * g * (L - s)
tau = rho * g * (L - s) / E
nf, st = rope["internal_force"][-1], rope["strain"][-1]
err = np.max(np.abs(nf[:, 2] / tension - 1))
check(err < 1e-3, "rope tension against rho A g (L - s): largest relative error %.2e" % err)
err = np.max(np.abs(st[:, 2] / (tau / (1 - tau)) - 1))
check(err < 1e-3, "rope axial strain against tau / (1 - tau): largest relative error %.2e" % err)
check(beam["curvature"].attrs["units"] == "rad/m" and rope["internal_force"].attrs["units"] == "N"
      and rope["strain"].attrs["units"] == "-" and beam["internal_couple"].attrs["units"] == "N m",
      "units of the new datasets")
check(list(rope["strain"].attrs["columns"]) == ["d1", "d2", "d3"], "material-frame columns")
# the groups describe themselves
a = beam.attrs
check(a["kind"] == "rod" and a["material"] == "rubber" and a["where"] == "statics.sinew:5",
      "beam: kind %s, material %s, where %s" % (a["kind"], a["material"], a["where"]))
check(a["elements"] == 40 and a["length"] == 0.3 and a["length_units"] == "m"
      and np.all(a["radius"] == 0.01) and len(a["radius"]) == 40 and a["radius_units"] == "m",
      "beam geometry with units")
check(a["E"] == 100e6 and a["E_units"] == "Pa" and abs(a["G"] - 100e6 / 3) < 1e-3
      and a["density"] == 1000 and a["density_units"] == "kg/m^3" and a["rigid"] == 0,
      "beam constants with units (G = E / 3 for poisson 0.5)")
root = f.attrs
check(root["dt_units"] == "s" and root["duration_units"] == "s" and root["duration"] == 1.0
      and root["gravity_units"] == "m/s^2", "root numbers with units")
p = f["params"][()]
check(len(p) == 1 and p[0]["name"] == b"g0" and p[0]["value"] == 9.81 and p[0]["unit"] == b"m/s^2"
      and p[0]["default"] == 9.81, "params table %s" % p)
sys.exit(1 if fails else 0)
EOF
ok $? "selected datasets and their statics, self-describing groups"
diag <"$TMP/out"

# joints and muscles: the angle and the force of one joint, the force of one
# muscle; the other joints (the shoulder, the muscles' attachments) and the
# other muscle keep nothing of those kinds, and every muscle its stretch
cat >"$TMP/arm.sinew" <<'EOF'
material bone { E = 15 GPa; density = 1.75 g/cm^3; }
material soft { E = 10 kPa; density = 1.06 g/cm^3; }
bone upper { material = bone; start = (0, 0, 0) m; direction = (0, 0, -1); normal = (1, 0, 0);
             length = 0.3 m; radius = 1 cm; elements = 6; }
bone fore { material = bone; start = (0, 0, -0.3) m; direction = (1, 0, 0); normal = (0, 0, 1);
            length = 0.25 m; radius = 8 mm; elements = 5; }
joint elbow = hinge(upper.end, fore.start) { axis = (0, 1, 0); stiffness = 1e5 N/m; }
joint shoulder = spherical(upper.start, (0, 0, 0) m) { stiffness = 1e5 N/m; }
muscle flexor { material = soft; from = upper.at(0.2); to = fore.at(0.1); filaments = 2;
                radius = 5 mm; sigma_max = 300 kPa; elements = 4; }
muscle extensor { material = soft; from = upper.at(0.3); to = fore.at(0.05); filaments = 2;
                  radius = 5 mm; sigma_max = 300 kPa; elements = 4; }
gravity (0, 0, -9.81) m/s^2;
simulate { duration = 2 ms; dt = 1 us; }
output "arm.h5" every 1 ms { angle elbow; force flexor, elbow; stretch all; positions upper; }
expect angle(elbow) at 2 ms in (-360 deg, 360 deg);
EOF
"$SC" "$TMP/arm.sinew" -o "$TMP/arm" 2>"$TMP/err"; ok $? "the arm compiles"
diag <"$TMP/err"
(cd "$TMP" && ./arm) >"$TMP/run" 2>&1; ok $? "it runs"
diag <"$TMP/run"
$PY - "$TMP/arm.h5" >"$TMP/out" 2>&1 <<'EOF'
import sys, h5py
f = h5py.File(sys.argv[1], "r")
names = []
f.visit(lambda n: names.append(n) if isinstance(f[n], h5py.Dataset) else None)
want = ["diagnostics/energy", "joints/elbow/angle", "joints/elbow/force",
        "muscles/extensor/activation",
        "muscles/extensor/filament_force", "muscles/extensor/stretch",
        "muscles/flexor/activation", "muscles/flexor/filament_force", "muscles/flexor/force",
        "muscles/flexor/stretch", "rods/upper/node_radius", "rods/upper/position", "time"]
print("datasets:", names)
# the checkpoint of SIM --restart is always there
ok = sorted(n for n in names if not n.startswith("restart/")) == want
ok &= "restart/state" in names and "restart/scalars" in names
j = f["joints/elbow"].attrs
ok &= j["kind"] == "hinge" and j["rod_a"] == "upper" and j["rod_b"] == "fore" \
      and list(j["axis"]) == [0, 1, 0] and j["stiffness"] == 1e5 and j["stiffness_units"] == "N/m"
print("elbow:", dict(j))
m = f["muscles/flexor"].attrs
ok &= m["kind"] == "muscle" and m["material"] == "soft" and m["F_max_units"] == "N" \
      and m["l0_units"] == "m" and m["where"] == "arm.sinew:9"
print("flexor:", dict(m))
sys.exit(0 if ok else 1)
EOF
ok $? "angle elbow; force flexor, elbow; stretch all; positions upper; write exactly those"
diag <"$TMP/out"
# the expectation reads the elbow, not the runtime's first joint (a muscle's
# attachment, numbered before the model's joints)
reported=$(sed -n 's/^ *value \([-0-9.e+]*\) deg.*/\1/p' "$TMP/run")
$PY -c "
import sys, h5py, math
a = h5py.File('$TMP/arm.h5', 'r')['joints/elbow/angle'][-1]
print('expectation %s deg, output %.6g deg' % ('$reported', math.degrees(a)))
sys.exit(0 if '$reported' and abs(float('$reported') - math.degrees(a)) < 1e-3 else 1)
" >"$TMP/out" 2>&1
ok $? "expect angle(elbow) reads the elbow in a scene whose muscles add joints"
diag <"$TMP/out"

done_testing
