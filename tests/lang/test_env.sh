#!/bin/sh
# test_env.sh — the generated C of environments (ground, terrain, fluid,
# contact, torque wave, probes, periodic and B-spline signals): deterministic, warning-free
# under -Wall -Wextra -Werror, one block per model line with its #line, rod
# lists resolved to runtime ids (a muscle's filaments, a component's rods,
# all), only the fields the model gave assigned, params as C over P; and the
# simulator runs, writes its HDF5 file with the model's source, and --info
# and --set work.
. "$(dirname "$0")/tap.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
CFLAGS_RT="-I$ROOT/runtime/include $(pkg-config --cflags hdf5 gsl 2>/dev/null)"

mkdir "$tmp/m"
cat > "$tmp/m/env.sinew" <<'MODEL'
param k = 100 N/m;
param visc = 1e-3 Pa s;
material tissue { E = 1 MPa; density = 1.1 g/cm^3; }
material soft { E = 10 kPa; density = 1.06 g/cm^3; }
component pair(y0) {
  rod left { material = tissue; start = (0 m, y0, 0 m); direction = (1, 0, 0); length = 10 cm; radius = 5 mm; elements = 10; }
  rod right { material = tissue; start = (0 m, y0 + 2 cm, 0 m); direction = (1, 0, 0); length = 10 cm; radius = 5 mm; elements = 10; }
}
use arm = pair(1 m);
rod snake { material = tissue; start = (0, 0, 0.01) m; direction = (1, 0, 0); length = 1 m; radius = 1 cm; elements = 20; }
muscle band { material = soft; from = arm.left.end; to = arm.right.end; radius = 2 mm; filaments = 3; elements = 4; sigma_max = 300 kPa; }
gravity (0, 0, -9.81) m/s^2;
ground floor { stiffness = k; mu_kinetic = (0.5, 0.7, 1); mu_static = 0.8; rods = snake; }
ground { stiffness = 10 N/m; }
terrain ramp_up { height(x, y) = 0.1 * x - 2 cm; stiffness = 1 N/m; rods = (arm.left, band); }
fluid water { viscosity = visc; rods = (band, snake); }
fluid air { model = quadratic; density = 1.2 kg/m^3; drag_coefficient = 1; flow = (1, 0, 0) m/s; }
contact touch { rods = (arm.left, arm.right); stiffness = 1e4 N/m; friction = 0.4; }
contact coil { rods = snake; stiffness = 1e4 N/m; self = true; static_friction = 0.6; kinetic_friction = 0.5; tangential_stiffness = 5e3 N/m; }
torque_wave body { rod = snake; coefficients = (0, 1, 2, 1, 0) mN m; wavelength = 0.5 m; period = 0.2 s; reverse = true; }
force snake.end = (0, 0, 1) mN * sine(1, 5 Hz, period = 0.1 s);
activate band = 0.5 * bspline(0, 1, 1, 0, over = 50 ms, from = 1 ms, period = 100 ms);
simulate { duration = 1 ms; }
output "env.h5" every 0.1 ms {
  probe com = centre_of_mass(all);
  probe head = snake.end;
  probe arm_speed = mean_velocity((arm.left, arm.right), window = 10 ms);
  probe band_velocity = velocity(band);
}
MODEL

cd "$tmp/m" || exit 1
"$SINEWC_ASAN" env.sinew --emit-c -o "$tmp/a.c"; ok $? "the environments model compiles to C"
"$SINEWC_ASAN" env.sinew --emit-c -o "$tmp/b.c"
cmp -s "$tmp/a.c" "$tmp/b.c"; ok $? "its C is deterministic"
out=$(cc -std=c11 -Wall -Wextra -Werror $CFLAGS_RT -c "$tmp/a.c" -o "$tmp/a.o" 2>&1); rc=$?
echo "$out" | diag; ok $rc "its C compiles with -Wall -Wextra -Werror"

has() {   # has PATTERN DESCRIPTION: a line of the C matches (grep -F)
  grep -qF -- "$1" "$tmp/a.c"; ok $? "$2"
}
# runtime ids: arm.left 0, arm.right 1, snake 2, band.f01..f03 3..5
has 'static const int rods[1] = {2};   /* snake */' "a rod list of one rod"
has 'static const int rods[4] = {0, 3, 4, 5};   /* arm.left, band */' \
    "a component's rod and a muscle's filaments in one list"
has 'static const int rods[4] = {3, 4, 5, 2};   /* band, snake */' "a muscle's filaments first when listed first"
grep -A4 'ground.name = "ground";' "$tmp/a.c" | grep -qF '/* every rod of the scene */'
ok $? "an unnamed ground is named after its kind and acts on every rod"
has '#line 14 "env.sinew"' "each environment block has its #line"
has '  /* ground floor { stiffness = k; mu_kinetic = (0.5, 0.7, 1); mu_static = 0.8; rods = snake; } */' \
    "and quotes its model line"
has 'ground.stiffness = P[0];' "a param-dependent field is C over P"
has 'fluid.viscosity = P[1];' "a param in a fluid"
has 'ground.mu_static[2] = 0.8;' "one friction number stands for all three directions"
grep -A14 'ground.name = "floor";' "$tmp/a.c" | grep -q 'slip_velocity\|origin\|normal'
[ $? -ne 0 ]; ok $? "fields the model did not give keep the runtime's defaults"
has 'ground.height = height_2;' "a terrain points at its height function"
has 'ground.height_ctx = height_P;' "and passes the params through ctx"
has 'fluid.model = SW_FLUID_QUADRATIC;' "the quadratic drag model"
has 'contact.self = 1;' "self-contact"
has 'contact.kinetic_friction = 0.4;' "one friction number is the kinetic coefficient"
has 'contact.static_friction = 0.4;' "and the static one"
has 'contact.static_friction = 0.6;' "a self-contact's own static coefficient"
has 'contact.tangential_stiffness = 5000.0;' "and its tangential stiffness, in N/m"
has 'wave.ncoef = 5;' "the wave's coefficient count"
has 'wave.coef[2] = 0.002;' "coefficients in SI (N m)"
has 'wave.reverse = 1;' "reverse"
has 'probe.kind = SW_PROBE_MEAN_VELOCITY;' "a mean-velocity probe"
has 'probe.window = 0.01;' "its window"
has 'probe.rod = 2; probe.node = 20;   /* snake */' "a point probe: rod and node"
has 'load.signal.period = 0.1;' "a periodic signal"
has 'muscle.activation.kind = SW_SIG_BSPLINE;' "a B-spline activation"
has 'muscle.activation.npts = 4;   /* B-spline coefficients */' "its coefficient count"
has 'muscle.activation.values[2] = 0.5;' "its coefficients, scaled by the factor in front"
has 'muscle.activation.T = 0.05;' "its span (over)"
has 'muscle.activation.t0 = 0.001;' "its start (from)"
has 'muscle.activation.period = 0.1;' "its period"

"$SINEWC_ASAN" env.sinew -o sim >"$tmp/out" 2>&1; rc=$?
diag <"$tmp/out"; ok $rc "the model compiles to a simulator"
./sim --quiet >"$tmp/out" 2>&1; rc=$?
diag <"$tmp/out"; ok $rc "the simulator runs"
[ -s env.h5 ]; ok $? "it writes env.h5"
if command -v h5dump >/dev/null 2>&1; then
  h5dump -a model_source env.h5 2>/dev/null | grep -q 'terrain ramp_up'
  ok $? "the HDF5 file holds the model source with its environments"
fi
./sim --info >"$tmp/info" 2>&1; rc=$?
[ $rc -eq 0 ] || diag <"$tmp/info"; ok $rc "--info runs"
grep -q 'visc = 0.001' "$tmp/info"; ok $? "--info lists the param of the fluid"
./sim --quiet --set 'k=200 N/m' --set 'visc=2e-3 Pa s' --out set.h5 >"$tmp/out" 2>&1; rc=$?
diag <"$tmp/out"; ok $rc "--set reaches the environments' params"
done_testing
