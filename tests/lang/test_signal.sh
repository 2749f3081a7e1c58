#!/bin/sh
# test_signal.sh — signal NAME(t) = ...;  the model's own time signals.
#
# 1. models/wing_drive.sinew, the wing muscles' forces of Zhang et al. 2019
#    (Suppl. eqs. 6-10), evaluated by the compiler (sinewc --eval-signal) at
#    times over the 0.51 s run against the equations as printed, written out
#    again here in awk, case by case, independently of the model's form.
# 2. The generated C (a harness includes it, builds the scene, compiles it
#    and evaluates each force's swSignal as the load kernel does) against
#    the compiler's evaluator, and a param reaching the signals through ctx.
# 3. A signal at work: a force that follows sup_force's initiation sine on a
#    free rod gives it the momentum of the impulse's closed form; gravity
#    switched on by a signal gives a free rod the velocity of its integral.
. "$(dirname "$0")/tap.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
CFLAGS_RT="-fopenmp -I$ROOT/runtime/include $(pkg-config --cflags hdf5 gsl 2>/dev/null)"
LIBS_RT="$ROOT/build/libsinewrt.a $(pkg-config --libs hdf5 gsl 2>/dev/null) -lm -fopenmp"
export SINEW_PATH="$ROOT/models"

# every 0.5 ms over the run, plus times just inside each piece's ends
awk 'BEGIN { for (k = 0; k <= 1020; k++) printf "%.6f\n", k * 0.0005 + 0.0001 }' >"$tmp/times"

cat > "$tmp/drive.sinew" <<'MODEL'
import "wing_drive.sinew";
material tissue { E = 1 MPa; density = 1000 kg/m^3; poisson = 0.5; }
rod a { material = tissue; from = (0, 0, 0) m; to = (1, 0, 0) m; radius = 1 cm; elements = 2; }
force a.end = (0, 0, 1) * bc_force;
force a.at(0.5) = (0, 0, 1) * st_force;
force a.start = (0, 0, 1) * pect_force;
torque a.end = (0, 0, 1) m * sup_force;
simulate { dt = 10 us; duration = 0.51 s; }
MODEL

"$SINEWC_ASAN" --eval-signal "$tmp/drive.sinew" <"$tmp/times" >"$tmp/eval"; ok $? "sinewc --eval-signal runs"
[ "$(grep -c . "$tmp/eval")" -eq $((8 * 1021)) ]; ok $? "it prints the 8 signals at the 1021 times"

# eqs. 6-10 as printed (T = 0.38 s; the cycle starts at 0.125 s)
awk -v T=0.38 '
  function w(x) { return sin(2 * 3.141592653589793 / (0.6579 * T) * x) }
  function bc(t,  u) { if (t < 0.125) return 0; u = (t - 0.125) % T
    if (u < 0.125 * T) return 9.83 * w(u + 0.0395 * T)
    if (u < 0.2895 * T) return 9.83 * (1 - 0.7 * (u - 0.125 * T) / (0.1645 * T))
    if (u < 0.4539 * T) return 2.95 * w(u - 0.125 * T)
    if (u < 0.9605 * T) return 0
    return 9.83 * w(u - 0.9605 * T) }
  function st(t,  u) { if (t < 0.0625) return 11.06 * sin(16 * 3.141592653589793 * t)
    if (t < 0.125) return 0; u = (t - 0.125) % T
    if (u < 0.3816 * T) return 0
    if (u < 0.5461 * T) return 3.28 * w(u - 0.3816 * T)
    if (u < 0.7105 * T) return 3.28 * (1 - 0.35 * (u - 0.5461 * T) / (0.1645 * T))
    if (u < 0.8750 * T) return 2.13 * w(u - 0.5461 * T)
    return 0 }
  function pect(t,  u) { if (t < 0.125) return 0; u = (t - 0.125) % T
    if (u < 0.125 * T) return 7.37 * w(u + 0.0395 * T)
    if (u < 0.2895 * T) return 7.37 * (1 - 0.5 * (u - 0.125 * T) / (0.1645 * T))
    if (u < 0.4539 * T) return 3.68 * w(u - 0.125 * T)
    if (u < 0.9605 * T) return 0
    return 7.37 * w(u - 0.9605 * T) }
  function sup(t,  u) { if (t < 0.125) return 6.14 * sin(8 * 3.141592653589793 * t)
    u = (t - 0.125) % T
    if (u < 0.4079 * T) return 0
    if (u < 0.5724 * T) return 7.37 * w(u - 0.4079 * T)
    if (u < 0.7368 * T) return 7.37 * (1 - 0.6 * (u - 0.5724 * T) / (0.1645 * T))
    if (u < 0.9013 * T) return 2.95 * w(u - 0.5724 * T)
    return 0 }
  $2 ~ /_force$/ {
    t = $3; name = $2
    ref = name == "bc_force" ? bc(t) : name == "st_force" ? st(t) : name == "pect_force" ? pect(t) : sup(t)
    d = $4 - ref; if (d < 0) d = -d
    if (d > worst) { worst = d; at = t; which = name }
    if ($4 > peak[name]) peak[name] = $4
    n++ }
  END { printf "# %d samples of the four forces against eqs. 6-10: largest difference %.3e N (%s at %.4f s)\n", n, worst, which, at
        printf "# peaks: BC %.3f N, ST %.3f N, PECT %.3f N, SUP %.3f N\n", peak["bc_force"], peak["st_force"], peak["pect_force"], peak["sup_force"]
        exit !(n == 4 * 1021 && worst < 1e-12) }' "$tmp/eval"
ok $? "the wing's muscle forces equal Suppl. eqs. 6-10 (within 1e-12 N)"

# 2. the generated C
"$SINEWC_ASAN" "$tmp/drive.sinew" --emit-c -o "$tmp/drive.c"; ok $? "the model compiles to C"
out=$(cc -std=c11 -Wall -Wextra -Werror $CFLAGS_RT -c "$tmp/drive.c" -o "$tmp/drive.o" 2>&1); rc=$?
echo "$out" | diag; ok $rc "its C compiles with -Wall -Wextra -Werror"
grep -q 'static double signal_7(double t, const void \*ctx)' "$tmp/drive.c"; ok $? "each signal is a swSignalFn"
grep -q 'load.signal = sw_signal_func(signal_4, signal_P, 0.0, 0.51);   /\* bc_force \*/' "$tmp/drive.c"
ok $? "the force holds its signal by name"

cat > "$tmp/harness.c" <<'HARNESS'
#include <stdlib.h>
#define main simulator_main
#include "drive.c"
#undef main
#include <stdio.h>

/* "k t value" for each load's signal at each t of stdin; argv[1] scales T */
int main(int argc, char **argv) {
  double P[1] = {params[0].value};
  if (argc > 1) P[0] *= atof(argv[1]);
  swSpec *s = sw_spec_new();
  char err[256];
  if (build(s, P, err, sizeof err) != SW_OK) return 1;
  swModel *m = sw_compile(s, err, sizeof err);
  if (!m) { fprintf(stderr, "%s\n", err); return 1; }
  double t;
  while (scanf("%lf", &t) == 1)
    for (int k = 0; k < m->nload; k++)
      printf("%d %.17g %.17g\n", k, t, sw_signal_eval(&m->load[k].signal, t));
  sw_model_free(m);
  sw_spec_free(s);
  return 0;
}
HARNESS
out=$(cd "$tmp" && cc -std=c11 -O2 -Wall $CFLAGS_RT harness.c -o harness $LIBS_RT 2>&1); rc=$?
echo "$out" | diag; ok $rc "the harness builds"
"$tmp/harness" <"$tmp/times" >"$tmp/gen"; ok $? "the harness runs"
# loads 0..3 are bc, st, pect, sup (signals 4..7)
awk 'NR == FNR { if ($2 ~ /_force$/) ev[$1 - 4, $3 + 0] = $4; next }
     { d = $3 - ev[$1, $2 + 0]; if (d < 0) d = -d; if (d > worst) worst = d; n++ }
     END { printf "# generated C vs the compiler evaluator, %d samples: largest difference %.3e N\n", n, worst
           exit !(n == 4 * 1021 && worst <= 1e-12) }' "$tmp/eval" "$tmp/gen"
ok $? "the generated signals equal the compiler's (within 1e-12 N)"

# the period is a param: doubled, SUP's first cycle peak (at tau = 0.4079 T +
# 0.6579 T / 4) moves from 0.342 s to 0.559 s
echo 0.5590 | "$tmp/harness" 2 | awk '$1 == 3 { printf "# SUP at 0.559 s with T = 0.76 s: %.6f N\n", $3; exit !($3 > 7.369 && $3 <= 7.37) }'
ok $? "a param in a signal is read from ctx (T doubled moves SUP's peak)"

# 3. the impulse of a signal: a free rod in space, pushed at its centre by
# sup_force's initiation pulse, 6.14 N sin(8 pi t), moves with
# p(t) = 6.14 / (8 pi) (1 - cos(8 pi t)) N s
cat > "$tmp/push.sinew" <<'MODEL'
import "wing_drive.sinew";
material tissue { E = 1 MPa; density = 1000 kg/m^3; poisson = 0.5; }
rod a { material = tissue; from = (0, 0, 0) m; to = (0.1, 0, 0) m; radius = 1 cm; elements = 2; }
force a.at(0.5) = (0, 0, 1) * sup_force;
simulate { dt = 10 us; duration = 0.1 s; }
output "push.h5" every 10 ms { probe p = velocity(a); }
MODEL
"$SINEWC" "$tmp/push.sinew" -o "$tmp/push" >/dev/null; ok $? "the pushed rod compiles"
(cd "$tmp" && ./push >/dev/null 2>&1); ok $? "it runs"
/usr/bin/python3 - "$tmp/push.h5" <<'PY'
import sys, math, h5py
f = h5py.File(sys.argv[1], "r")
t = f["/time"][:]
v = f["/probes/p"][:]
m = 1000 * math.pi * 0.01**2 * 0.1
worst = 0
for k in range(len(t)):
    p = 6.14 / (8 * math.pi) * (1 - math.cos(8 * math.pi * t[k]))
    worst = max(worst, abs(m * v[k][2] - p) / (6.14 / (8 * math.pi)))
print("# momentum of the pushed rod against the impulse's closed form: largest difference %.2e of 6.14 N / (8 pi)" % worst)
sys.exit(0 if worst < 1e-6 else 1)
PY
ok $? "the momentum it gains is the impulse of the signal (within 1e-6)"

# gravity times a signal: switched on at 50 ms as 1 - exp(-(t - 50 ms) / 10 ms),
# a free rod falls with v(t) = -g (s - tau (1 - exp(-s / tau))), s = t - 50 ms
cat > "$tmp/fall.sinew" <<'MODEL'
material tissue { E = 1 MPa; density = 1000 kg/m^3; poisson = 0.5; }
rod a { material = tissue; from = (0, 0, 0) m; to = (0.1, 0, 0) m; radius = 1 cm; elements = 2; }
signal onset(t) = piecewise(t < 50 ms: 0, 1 - exp(-(t - 50 ms) / 10 ms));
gravity (0, 0, -9.81) m/s^2 * onset;
simulate { dt = 10 us; duration = 0.1 s; }
output "fall.h5" every 10 ms { probe v = velocity(a); }
MODEL
"$SINEWC" "$tmp/fall.sinew" -o "$tmp/fall" >/dev/null 2>&1 && (cd "$tmp" && ./fall --quiet) >/dev/null 2>&1
ok $? "gravity times a signal compiles and runs"
/usr/bin/python3 - "$tmp/fall.h5" <<'PY'
import sys, math, h5py
f = h5py.File(sys.argv[1], "r")
worst = 0
for t, v in zip(f["/time"][:], f["/probes/v"][:]):
    s = max(0.0, t - 0.05)
    worst = max(worst, abs(v[2] + 9.81 * (s - 0.01 * (1 - math.exp(-s / 0.01)))))
print("# the falling rod's velocity against the integral of g s(t): largest difference %.2e m/s" % worst)
sys.exit(0 if worst < 1e-7 else 1)
PY
ok $? "it falls with the integral of g times the signal (within 1e-7 m/s)"

done_testing
