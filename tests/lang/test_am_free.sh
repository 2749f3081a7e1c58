#!/bin/sh
# test_am_free.sh — the free artificial muscle (AM) in isolation, against
# closed forms: the twisted coil of Zhang et al. 2019 (Table 3: E 30 GPa,
# 1.67 g/cm^3, helix radius R = 10 mm, 9 turns on a 0.425 m core, filament
# a = 5 mm), its filament radius growing as r = a (1 + rate t), its rest
# twist k3 ~ a / r (mattialab/elastica source/Polymer.cpp), variational law.
#
#   held      both ends clamped: the axial force (the internal force of the
#             middle half, in the lab frame) against Kirchhoff's helical
#             spring held at its ends, F = C (tau - tau a / r) cos(alpha) / R,
#             C = G pi r^4 / 2 (docs/physics.md, "A twisted coil held at its
#             ends"), at r = 1.02 a: converged in elements (12, 24, 48 a
#             turn) at a / R = 1/8, and the thick filament's departure,
#             falling as (a / R)^2, at a / R = 1/2, 1/4, 1/8
#   example   examples/am_free.sinew: its held coil's /joints/hold/force
#             equals the clamped coil's force (the holding spring is stiff)
#   rate      the held AM at release rates 0.25, 0.5, 1 /s: at each time a
#             higher rate gives more force (Zhang et al. 2019, Suppl. Fig.
#             7c), and at a given radius the force is the same at every rate
#             (quasi-static: the force follows r only)
#   free      a free coil (a = 2.5 mm, 3 turns, 12, 24, 48 elements a turn)
#             released to r = 2 a over 0.1 s: its end-to-end length at
#             r = 1.25, 1.5, 1.75, 2 a against the helix of curvature kappa and
#             torsion tau a / r, converging at second order in the element
. "$(dirname "$0")/tap.sh"
scratch am_free
PY=/usr/bin/python3
SC=$SINEWC_CHECK

# coil NAME TURNS PER_TURN HELD: a model with params a (filament radius),
# rate (release) and grow (r / a at the end of the release)
coil() {
  core=$($PY -c "print(0.425 * $2 / 9)")
  cat > "$TMP/$1.sinew" <<MODEL
param a = 5 mm;
param rate = 10 /s;
param damp = 5 kg/m/s;
material am_fibre { E = 30 GPa; density = 1.67 g/cm^3; poisson = 0.5; variational = true; }
rod am {
  material = am_fibre;
  start = (0, 0, 0) m;
  direction = (0, 0, 1);
  normal = (1, 0, 0);
  shape = helix(radius = 10 mm, turns = $2, core = $core m);
  radius = a * ramp(1, 2, over = 1 / rate);
  rest_twist_scale = follows_radius;
  mass = conserved;
  damping = damp;
  elements = $(($2 * $3));
}
clamp am.start;
$([ "$4" = held ] && echo "clamp am.end;")
simulate { duration = 10 ms; }
output "$1.h5" every 1 ms { positions am; internal_force am; directors am; }
MODEL
  "$SC" "$TMP/$1.sinew" -o "$TMP/$1" >"$TMP/out" 2>&1 || diag <"$TMP/out"
}
# run NAME OUT ARGS...: at 0.9 of its stable estimate
run() {
  name=$1 out=$2; shift 2
  est=$("$TMP/$name" --info "$@" | sed -n 's/.*stable estimate \([0-9.]*\) ns).*/\1/p' | tail -1)
  (cd "$TMP" && ./$name --quiet --dt "$($PY -c "print(0.9 * $est)")ns" --out "$out.h5" "$@") \
    >"$TMP/$out.log" 2>&1 || { echo "# $out failed"; diag <"$TMP/$out.log"; }
}

# ---- held: Kirchhoff's helical spring
for n in 12 24 48; do coil held$n 9 $n held; done
run held12 h12_a5 --duration 6ms --set a=5mm
run held12 h12_a2.5 --duration 6ms --set a=2.5mm
for n in 12 24 48; do run held$n h${n}_a1.25 --duration 6ms --set a=1.25mm; done
cat > "$TMP/am.py" <<'PY'
import math, h5py, numpy as np
R, core9, G = 0.01, 0.425, 1e10
c = core9 / 9 / (2 * math.pi); q = R * R + c * c
kappa, tau, cos_a = R / q, c / q, R / math.sqrt(q)
L = 2 * math.pi * 9 * math.sqrt(q)
def kirchhoff(r, a):          # F of the held helical spring, Love
    return G * math.pi * r**4 / 2 * tau * (1 - a / r) * cos_a / R
def axial(fn):                # time, axial force of the middle half, its spread
    f = h5py.File(fn, "r")
    n = f["/rods/am/internal_force"][:]; Q = f["/rods/am/directors"][:]
    Fz = np.einsum("fnij,fni->fnj", Q, n)[:, :, 2]
    m = Fz.shape[1]; mid = Fz[:, m // 4: 3 * m // 4]
    return f["/time"][:], mid.mean(axis=1), mid.std(axis=1) / abs(mid.mean(axis=1))
def helix_span(k, t, L):      # end-to-end length of a helix of arc length L
    qq = k * k + t * t; Rh, ch, th = k / qq, t / qq, L * math.sqrt(qq)
    return math.sqrt((ch * th) ** 2 + (2 * Rh * math.sin(th / 2)) ** 2)
PY
$PY - "$TMP" >"$TMP/held.out" 2>&1 <<'PY'
import sys; sys.path.insert(0, sys.argv[1]); from am import *
def ratio(name, a):
    t, F, spread = axial(f"{sys.argv[1]}/{name}.h5")
    r = a * (1 + 10 * t[-1])
    return F[-1] / kirchhoff(r, a), spread[-1], F[-1], r
ok = True
v = {}
for name, a in [("h12_a5", 5e-3), ("h12_a2.5", 2.5e-3), ("h12_a1.25", 1.25e-3),
                ("h24_a1.25", 1.25e-3), ("h48_a1.25", 1.25e-3)]:
    v[name], spread, F, r = ratio(name, a)
    print(f"{name}: r = {r*1e3:.4f} mm, F = {F:.5g} N, F / F_Kirchhoff = {v[name]:.5f}, "
          f"spread along the middle half {spread:.1e}")
    ok &= spread < 1e-3
d1 = v["h12_a1.25"] - v["h24_a1.25"]; d2 = v["h24_a1.25"] - v["h48_a1.25"]
order = math.log2(d1 / d2); limit = v["h48_a1.25"] - d2 / 3
print(f"a/R = 1/8, 12 -> 24 -> 48 elements a turn: differences {d1:.2e}, {d2:.2e} (order {order:.2f}); "
      f"extrapolated F / F_Kirchhoff = {limit:.5f}")
ok &= 1.5 < order < 3.5 and abs(limit - 1) < 0.01
s = (v["h12_a2.5"] - v["h12_a5"]) / (v["h12_a1.25"] - v["h12_a2.5"])
print(f"thick filament, 12 a turn: F / F_Kirchhoff {v['h12_a5']:.4f}, {v['h12_a2.5']:.4f}, "
      f"{v['h12_a1.25']:.4f} at a/R = 1/2, 1/4, 1/8: steps in the ratio {s:.2f} ((a/R)^2: 4)")
ok &= 3 < s < 5
sys.exit(0 if ok else 1)
PY
ok $? "held: the blocked force converges to Kirchhoff's helical spring (elements, then a/R)"
diag <"$TMP/held.out"

# ---- the example: the holding spring's force is the clamped coil's
"$SC" "$ROOT/examples/am_free.sinew" -o "$TMP/am_free" >"$TMP/out" 2>&1
ok $? "am_free.sinew compiles"
(cd "$TMP" && ./am_free --quiet --duration 20ms --dt 500ns --out ex.h5) >"$TMP/out" 2>&1
ok $? "am_free.sinew runs 20 ms"
run held12 h12_ex --duration 20ms --set a=5mm --set rate=1Hz
$PY - "$TMP" >"$TMP/ex.out" 2>&1 <<'PY'
import sys; sys.path.insert(0, sys.argv[1]); from am import *
f = h5py.File(sys.argv[1] + "/ex.h5", "r")
tj, Fj = f["/time"][:], f["/joints/hold/force"][:, 2]
t, F, _ = axial(sys.argv[1] + "/h12_ex.h5")
i = int(np.argmin(abs(tj - 0.02))); k = int(np.argmin(abs(t - 0.02)))
K = kirchhoff(5e-3 * 1.02, 5e-3)
print(f"am_free.sinew at 20 ms (r = 1.02 a): joint 'hold' {Fj[i]:.5g} N, the clamped coil {F[k]:.5g} N "
      f"(difference {Fj[i]/F[k]-1:+.2e}); Kirchhoff {K:.5g} N")
sys.exit(0 if abs(Fj[i] / F[k] - 1) < 5e-3 else 1)
PY
ok $? "am_free.sinew: the holding joint's force is the clamped coil's"
diag <"$TMP/ex.out"

# ---- rate: more force at a given time, the same force at a given radius
for rate in 0.25 0.5 1; do run held12 rate$rate --duration 40ms --set a=5mm --set rate=${rate}Hz; done
$PY - "$TMP" >"$TMP/rate.out" 2>&1 <<'PY'
import sys; sys.path.insert(0, sys.argv[1]); from am import *
ok = True; runs = {r: axial(f"{sys.argv[1]}/rate{r:g}.h5")[:2] for r in (0.25, 0.5, 1.0)}
def at(rate, T): t, F = runs[rate]; return F[int(np.argmin(abs(t - T)))]
for T in (0.01, 0.02, 0.04):
    Fs = [at(r, T) for r in (0.25, 0.5, 1.0)]
    print(f"t = {T*1e3:.0f} ms: F = {Fs[0]:.4g}, {Fs[1]:.4g}, {Fs[2]:.4g} N at 0.25, 0.5, 1 /s")
    ok &= Fs[0] < Fs[1] < Fs[2]
for g in (1.01, 1.02):             # the same radius, reached at different times
    Fs = [(r, at(r, (g - 1) / r)) for r in (0.25, 0.5, 1.0) if (g - 1) / r <= 0.04 + 1e-9]
    spread = max(F for _, F in Fs) / min(F for _, F in Fs) - 1
    print(f"r = {g} a: F = " + ", ".join(f"{F:.5g} N at {r:g} /s" for r, F in Fs)
          + f" (spread {spread:.1e}); Kirchhoff {kirchhoff(5e-3 * g, 5e-3):.5g} N")
    ok &= spread < 2e-3
sys.exit(0 if ok else 1)
PY
ok $? "rate: a higher rate gives more force at a given time, the same at a given radius"
diag <"$TMP/rate.out"

# ---- free: the stroke against the helix of the released twist
for n in 12 24 48; do coil free$n 3 $n free; run free$n f$n --duration 110ms --set a=2.5mm; done
$PY - "$TMP" >"$TMP/free.out" 2>&1 <<'PY'
import sys; sys.path.insert(0, sys.argv[1]); from am import *
L3 = L / 3; ok = True; err = {}
for n in (12, 24, 48):
    f = h5py.File(f"{sys.argv[1]}/f{n}.h5", "r")
    t = f["/time"][:]; x = f["/rods/am/position"][:]
    span = np.linalg.norm(x[:, -1] - x[:, 0], axis=1)
    err[n] = []
    for g in (1.25, 1.5, 1.75, 2.0):
        i = int(np.argmin(abs(t - (g - 1) / 10)))
        ref = helix_span(kappa, tau / g, L3)
        err[n].append(span[i] / ref - 1)
    print(f"{n} a turn: end-to-end {span[0]:.5f} m at r = a; at r/a = 1.25, 1.5, 1.75, 2: "
          + ", ".join(f"{e:+.2e}" for e in err[n]) + " from the helix of torsion tau a/r")
for j, g in enumerate((1.25, 1.5, 1.75, 2.0)):
    o = math.log2(abs(err[12][j] / err[24][j])), math.log2(abs(err[24][j] / err[48][j]))
    print(f"r/a = {g}: the helix {helix_span(kappa, tau / g, L3):.5f} m; orders {o[0]:.2f}, {o[1]:.2f}")
    ok &= abs(err[48][j]) < 1e-3 and abs(err[12][j]) > abs(err[24][j]) > abs(err[48][j])
sys.exit(0 if ok else 1)
PY
ok $? "free: the stroke follows the helix of the released twist, converging in the element"
diag <"$TMP/free.out"
done_testing
