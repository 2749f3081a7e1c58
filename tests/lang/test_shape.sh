#!/bin/sh
# test_shape.sh — rods that rest or start in a shape (shape, rest_shape,
# start_shape), end to end from the language, against closed forms.
#
#   helix     shape = helix(radius, turns, core) at 12, 24 and 48 elements a
#             turn: the nodes at t = 0 on the closed-form helix (radius R
#             about the axis through start + R normal, rise c = pitch / 2 pi
#             per radian, right- and left-handed), and the curvature the
#             runtime computes (output `curvature`) against
#             kappa = R / (R^2 + c^2) about d2 and tau = +-c / (R^2 + c^2)
#             about d3, converging at second order (orders printed)
#   at rest   the right-handed coil, free, after 1000 steps: its largest
#             node speed (round-off)
#   coiling   a rod resting as a 3-turn helix, started straight, damped and
#             free: its end-to-end distance reaches the helix's core and
#             every node-to-node distance the helix's
#   catenary  a cable of length L pinned at two points D apart at one
#             height: started in its catenary (start_shape(s), the arc
#             length from the lowest point u = s - L/2: x = a asinh(u / a),
#             z = sqrt(a^2 + u^2), 2 a sinh(D / 2a) = L), it stays near
#             still under gravity (drift printed); started straight and
#             compressed to the span (start_shape(s) = (s D / L, 0, 0),
#             stretch 0.8), it sags into the catenary (damped at 0.2 N s/m^2:
#             at 0.05 the released compression, 100 times the weight's work,
#             throws a loop into the cable at some steps, which it keeps):
#             the sag
#             sqrt(a^2 + L^2 / 4) - a within 0.5 %, the cable's stretch
#             (rho g (a + sag) / E = 0.06 %) and bending (length
#             (E I / rho A g)^(1/3) = 6 cm) moving it by 0.1 to 0.2 %
#   C         the generated C compiles with -Wall -Wextra -Werror and holds
#             the curve as a function of s
. "$(dirname "$0")/tap.sh"
scratch shape
PY=/usr/bin/python3
SC=$SINEWC_CHECK

# ---- the helix: geometry and curvature at three resolutions
for per in 12 24 48; do
  for hand in right left; do
    cat > "$TMP/helix_${hand}_$per.sinew" <<MODEL
material polymer { E = 1 MPa; density = 1.67 g/cm^3; poisson = 0.5; }
rod coil {
  material = polymer;
  start = (1, 2, 3) cm;
  direction = (0, 1, 1);
  normal = (1, 0, 0);
  shape = helix(radius = 10 mm, turns = 9, core = 0.425 m, hand = $hand);
  radius = 2 mm;
  elements = $((9 * per));
}
simulate { dt = 10 us; duration = 10 ms; }
output "helix.h5" every 10 ms { positions; curvature; velocity; }
MODEL
    "$SC" "$TMP/helix_${hand}_$per.sinew" -o "$TMP/helix_${hand}_$per" >"$TMP/out" 2>&1
    rc=$?; ok $rc "helix, $hand-handed, $per elements a turn: compiles"
    [ $rc -eq 0 ] || diag <"$TMP/out"
    (cd "$TMP" && "./helix_${hand}_$per" --quiet --out "helix_${hand}_$per.h5") >"$TMP/out" 2>&1
    rc=$?; ok $rc "helix, $hand-handed, $per elements a turn: runs 1000 steps"
    [ $rc -eq 0 ] || diag <"$TMP/out"
  done
done
$PY - "$TMP" >"$TMP/helix.out" 2>&1 <<'PY'
import sys, math
import h5py, numpy as np
tmp = sys.argv[1]
R, core, N = 0.01, 0.425, 9
c = core / N / (2 * math.pi)
kappa, tau = R / (R * R + c * c), c / (R * R + c * c)
arc = 2 * math.pi * N * math.sqrt(R * R + c * c)
start = np.array([0.01, 0.02, 0.03]); a = np.array([0, 1, 1]) / math.sqrt(2); n0 = np.array([1.0, 0, 0])
print(f"# helix R = {R} m, core {core} m, {N} turns: kappa = {kappa:.6g} 1/m, tau = {tau:.6g} 1/m, arc {arc:.6g} m")
bad = 0
for hand, h in (("right", 1), ("left", -1)):
    errs = []
    for per in (12, 24, 48):
        with h5py.File(f"{tmp}/helix_{hand}_{per}.h5") as f:
            x = f["/rods/coil/position"][0]
            k = f["/rods/coil/curvature"][0]
            v = f["/rods/coil/velocity"][-1]
        n = 9 * per
        th = 2 * math.pi * N * np.arange(n + 1) / n
        e1 = -n0; e2 = h * np.cross(a, e1)
        ref = start + R * n0 + R * (np.cos(th)[:, None] * e1 + np.sin(th)[:, None] * e2) + c * th[:, None] * a
        node = np.abs(x - ref).max()
        eb = max(np.abs(k[:, 0]).max(), np.abs(k[:, 1] - kappa).max()) / kappa
        et = np.abs(k[:, 2] - h * tau).max() / tau
        length = np.linalg.norm(np.diff(x, axis=0), axis=1).sum()
        el = abs(length / arc - 1)
        vmax = np.linalg.norm(v, axis=1).max()
        errs.append((eb, et, el))
        print(f"# {hand}, {per:2d} a turn: node off the helix {node:.2e} m, curvature d1,d2 rel. error {eb:.3e}, "
              f"twist rel. error {et:.3e}, length rel. error {el:.3e}; after 1000 steps, largest speed {vmax:.2e} m/s")
        if node > 1e-15 or vmax > 1e-9: bad += 1
    for i in range(2):
        o = [math.log2(errs[i][j] / errs[i + 1][j]) for j in range(3)]
        print(f"# {hand}, order {12 << i} -> {24 << i} a turn: curvature {o[0]:.3f}, torsion {o[1]:.3f}, length {o[2]:.3f}")
        if any(abs(oj - 2) > 0.1 for oj in o): bad += 1
    if errs[0][0] > 0.005 or errs[0][1] > 0.02: bad += 1
sys.exit(1 if bad else 0)
PY
rc=$?; diag <"$TMP/helix.out"
ok $rc "the helix's nodes, curvature, torsion and length against the closed form, second order; still after 1000 steps"

# ---- a straight rod resting as a helix coils into it
cat > "$TMP/coiling.sinew" <<'MODEL'
material soft { E = 1 MPa; density = 1000 kg/m^3; poisson = 0.5; }
rod spring {
  material = soft;
  start = (0, 0, 0) m;
  direction = (1, 0, 0);
  normal = (0, 0, 1);
  rest_shape = helix(radius = 2 cm, turns = 3, pitch = 3 cm);
  radius = 2 mm;
  elements = 72;
  damping = 0.2 N s/m^2;
}
simulate { duration = 3 s; }
output "coiling.h5" every 50 ms;
MODEL
"$SC" "$TMP/coiling.sinew" -o "$TMP/coiling" >"$TMP/out" 2>&1 &&
  (cd "$TMP" && ./coiling --quiet) >>"$TMP/out" 2>&1
rc=$?; ok $rc "a straight rod resting as a helix compiles and runs 3 s"
[ $rc -eq 0 ] || diag <"$TMP/out"
$PY - "$TMP" >"$TMP/coiling.out" 2>&1 <<'PY'
import sys, math
import h5py, numpy as np
with h5py.File(sys.argv[1] + "/coiling.h5") as f:
    x = f["/rods/spring/position"][:]
R, P, n = 0.02, 0.03, 72
e = np.linalg.norm(x[:, -1] - x[:, 0], axis=1)
th = np.linspace(0, 6 * math.pi, n + 1)
h = np.stack([R * np.cos(th), R * np.sin(th), P / (2 * math.pi) * th], 1)
dm = lambda y: np.linalg.norm(y[:, None] - y[None], axis=2)
pair = np.abs(dm(x[-1]) - dm(h)).max()
print(f"# end-to-end: {e[0]:.4f} m straight, {e[10]:.4f} m at 0.5 s, {e[-1]:.6f} m at 3 s; the helix's core {3 * P} m")
print(f"# largest node-to-node distance off the helix's at 3 s: {pair:.2e} m")
sys.exit(0 if abs(e[-1] / (3 * P) - 1) < 1e-3 and pair < 1e-5 else 1)
PY
rc=$?; diag <"$TMP/coiling.out"
ok $rc "released straight, it coils into its rest helix (end-to-end distance and shape)"

# ---- the catenary
a=$($PY -c '
import math
lo, hi = 0.1, 2.0
for _ in range(200):
    a = 0.5 * (lo + hi)
    if 2 * a * math.sinh(0.4 / a) > 1: lo = a
    else: hi = a
print(repr(a))')
for start in catenary straight; do
  if [ $start = catenary ]; then
    form='start_shape(s) = (a * log((s - L/2) / a + sqrt(((s - L/2) / a)^2 + 1)), 0 m, sqrt(a^2 + (s - L/2)^2));'
  else
    form='start_shape(s) = (s * D / L, 0 m, 0 m);'
  fi
  cat > "$TMP/$start.sinew" <<MODEL
let L = 1 m;
let D = 0.8 m;
let a = $a m;
material rubber { E = 10 MPa; density = 1000 kg/m^3; poisson = 0.5; }
rod cable {
  material = rubber;
  start = (0, 0, 0) m;
  normal = (0, 1, 0);
  length = L;
  $form
  radius = 1 mm;
  elements = 50;
  damping = 0.2 N s/m^2;
}
joint left = spherical(cable.start, (0, 0, 0) m);
joint right = spherical(cable.end, (0.8, 0, 0) m);
gravity (0, 0, -9.81) m/s^2;
simulate { duration = 3 s; }
output "$start.h5" every 20 ms;
MODEL
  [ $start = straight ] && sed -i 's/^let a = .*//' "$TMP/$start.sinew"
  "$SC" "$TMP/$start.sinew" -o "$TMP/$start" >"$TMP/out" 2>&1 &&
    (cd "$TMP" && "./$start" --quiet) >>"$TMP/out" 2>&1
  rc=$?; ok $rc "the cable started $start compiles and runs 3 s"
  [ $rc -eq 0 ] || diag <"$TMP/out"
done
$PY - "$TMP" "$a" >"$TMP/catenary.out" 2>&1 <<'PY'
import sys, math
import h5py, numpy as np
a = float(sys.argv[2]); L = 1.0
sag = math.sqrt(a * a + L * L / 4) - a
res = {}
for start in ("catenary", "straight"):
    with h5py.File(f"{sys.argv[1]}/{start}.h5") as f:
        x = f["/rods/cable/position"][:]
    s = -x[:, :, 2].min(1)
    res[start] = (x, s)
x, s = res["catenary"]
drift = np.abs(x - x[0]).max()
print(f"# catenary a = {a:.6f} m, sag {sag:.6f} m; started in it: sag at t = 0 {s[0]:.6f} m, "
      f"largest drift of a node over 3 s {drift:.2e} m ({drift / sag:.2%} of the sag)")
x, s2 = res["straight"]
print(f"# started straight (stretch 0.8): sag at 3 s {s2[-1]:.6f} m, {s2[-1] / sag - 1:+.3%} off the closed form; "
      f"moved {np.abs(x[-1] - x[-10]).max():.1e} m over its last 0.2 s")
ok = abs(s[0] / sag - 1) < 1e-12 and drift < 0.005 * sag and abs(s2[-1] / sag - 1) < 0.005
ok = ok and np.abs(x[-1] - x[-10]).max() < 1e-4
sys.exit(0 if ok else 1)
PY
rc=$?; diag <"$TMP/catenary.out"
ok $rc "a cable started in its catenary stays near still; one started straight sags into it (0.5 %)"

# ---- the generated C
"$SC" "$TMP/catenary.sinew" --emit-c -o "$TMP/catenary.c" >"$TMP/out" 2>&1
ok $? "the catenary model emits C"
CFLAGS_RT="-fopenmp -I$ROOT/runtime/include $(pkg-config --cflags hdf5 gsl 2>/dev/null)"
out=$(cc -std=c11 -Wall -Wextra -Werror $CFLAGS_RT -c "$TMP/catenary.c" -o "$TMP/catenary.o" 2>&1)
rc=$?; echo "$out" | diag; ok $rc "its C compiles with -Wall -Wextra -Werror"
grep -q 'static void shape_0(double s, double r\[3\], const void \*ctx)' "$TMP/catenary.c" &&
  grep -q 'sw_shape_curve(50, rod.length, shape_0, rod.start, rod.normal' "$TMP/catenary.c"
ok $? "the curve is a swCurveFn of s, given to sw_shape_curve"

done_testing
