#!/bin/sh
# test_muscle.sh — muscles, activate, passive and rigid in the generated C:
# one swMuscleDesc per muscle (sw_muscle_desc_init, then only the fields the
# model writes, then sw_spec_add_muscle) with #line back to the model; rod
# ids of everything after a muscle shifted by its filaments (joints, clamps,
# loads, attachments); the activation folded into one swSignal, param scale
# included; passive filaments 0-based; components prefix muscle names.  Then
# a compiled scene with a muscle runs and writes /muscles/NAME/force.
. "$(dirname "$0")/tap.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
CFLAGS_RT="-I$ROOT/runtime/include $(pkg-config --cflags hdf5 gsl 2>/dev/null)"
has() { grep -Fq -- "$1" "$tmp/arm.c"; }

# rods: humerus 0; biceps (18 filaments) 1-18; forearm 19; brachialis (2) 20-21; hand 22
cat > "$tmp/arm.sinew" <<'MODEL'
material bone { E = 15 GPa; density = 1.75 g/cm^3; }
material flesh { E = 10 kPa; density = 1.06 g/cm^3; }
param strength = 1;
bone humerus { material = bone; start = (0, 0, 0) m; direction = (0, 0, -1);
               length = 30 cm; radius = 1 cm; elements = 10; rigid = true; }
muscle biceps {
  material = flesh;
  from = humerus.at(0.1);
  to = (2, 0, -28) cm;
  radius = 2 cm;
  filaments = 18;
  motor_units = 360;
  elements = 6;
  sigma_max = 300 kPa;
  v_max = 6 / s;
}
bone forearm { material = bone; start = (0, 0, -30) cm; direction = (1, 0, 0);
               length = 25 cm; radius = 8 mm; elements = 10; }
muscle brachialis { material = flesh; from = humerus.at(0.5); to = forearm.at(0.2);
                    radius = 5 mm; filaments = 2; sigma_max = 250 kPa; }
rod hand { material = bone; start = (25, 0, -30) cm; direction = (1, 0, 0);
           length = 5 cm; radius = 5 mm; elements = 4; }
joint elbow = hinge(humerus.end, forearm.start) { axis = (0, 1, 0); }
joint wrist = spherical(forearm.end, hand.start);
clamp humerus.start;
force hand.end = (0, 0, -1) mN;
activate biceps = strength * ramp(0, 1, over = 20 ms);
activate brachialis = 0.25;
passive biceps.filament(3);
simulate { dt = 1 us; duration = 2 ms; }
output "arm.h5" every 0.5 ms;
MODEL
(cd "$tmp" && "$SINEWC_ASAN" arm.sinew --emit-c -o arm.c) >"$tmp/log" 2>&1; rc=$?
diag <"$tmp/log"; ok $rc "a scene with muscles compiles to C"
(cd "$tmp" && "$SINEWC_ASAN" arm.sinew --emit-c -o arm2.c)
cmp -s "$tmp/arm.c" "$tmp/arm2.c"; ok $? "its C is deterministic"
out=$(cc -std=c11 -Wall -Wextra -Werror $CFLAGS_RT -c "$tmp/arm.c" -o "$tmp/arm.o" 2>&1); rc=$?
echo "$out" | diag; ok $rc "its C compiles with -Wall -Wextra -Werror"

# the muscle block
n=$(grep -c 'sw_muscle_desc_init(&muscle);' "$tmp/arm.c")
[ "$n" -eq 2 ]; ok $? "sw_muscle_desc_init once per muscle ($n)"
n=$(grep -c 'ok &= sw_spec_add_muscle(s, &muscle) >= 0;' "$tmp/arm.c")
[ "$n" -eq 2 ]; ok $? "sw_spec_add_muscle once per muscle ($n)"
grep -q '^#line 6 "arm.sinew"$' "$tmp/arm.c" && grep -q '^  /\* muscle biceps { \*/$' "$tmp/arm.c"
ok $? "#line and the quoted model line head the muscle's block"
has 'muscle.name = "biceps";   /* muscle 0: filaments are rods 1 to 18 */'; ok $? "the muscle's name and its rods"
has 'muscle.filaments = 18;' && has 'muscle.nelem = 6;' && has 'muscle.motor_units = 360;'
ok $? "filaments, elements and motor units"
has 'muscle.sigma_max = 300000.0;' && has 'muscle.radius = 0.02;' && has 'muscle.v_max = 6.0;' &&
  has 'muscle.youngs = 10000.0;' && has 'muscle.density = 1060.0;'
ok $? "sigma_max, radius, v_max and the material in SI"
has 'muscle.attach_rod[0] = 0; muscle.attach_node[0] = 1;   /* humerus */'
ok $? "from = humerus.at(0.1) ties the start to node 1 of rod 0"
[ "$(grep -c 'muscle.attach_rod\[1\] = ' "$tmp/arm.c")" -eq 1 ]
ok $? "a position leaves the end untied (only brachialis ties its end)"
! has 'muscle.hill_a' && ! has 'muscle.size_ratio' && ! has 'muscle.twitch_small' && ! has 'muscle.normal'
ok $? "fields the model does not write keep the runtime's defaults"
awk '/muscle biceps/,/sw_spec_add_muscle/' "$tmp/arm.c" > "$tmp/biceps.c"
grep -q '^#line 27 "arm.sinew"$' "$tmp/biceps.c" &&
  grep -q '/\* activate biceps = strength \* ramp(0, 1, over = 20 ms); \*/' "$tmp/biceps.c"
ok $? "the activation is set in the muscle's block under the activate line's #line"
grep -q 'muscle.activation.kind = SW_SIG_RAMP;' "$tmp/biceps.c" &&
  grep -q 'muscle.activation.b = .*P\[0\]' "$tmp/biceps.c" && grep -q 'muscle.activation.T = 0.02;' "$tmp/biceps.c"
ok $? "a ramp scaled by a param: the scale folded into the signal's values"
has 'muscle.activation = sw_signal_const(0.25);'; ok $? "a constant activation"
has 'ok &= sw_spec_set_filament_passive(s, 0, 2) == SW_OK;   /* biceps, filament 3 */'
ok $? "passive biceps.filament(3) is filament 2 of muscle 0"
has 'rod.rigid = 1;'; ok $? "rigid = true sets rod.rigid"
[ "$(grep -c 'rod.rigid' "$tmp/arm.c")" -eq 1 ]; ok $? "only the rigid rod sets it"

# rod ids after the muscles
has 'rod.name = "forearm";   /* bone, rod 19 */'; ok $? "the rod after an 18-filament muscle is rod 19"
has 'rod.name = "hand";   /* rod, rod 22 */'; ok $? "the rod after both muscles is rod 22"
has 'muscle.attach_rod[1] = 19; muscle.attach_node[1] = 2;   /* forearm */'
ok $? "brachialis is tied to rod 19 (forearm), node 2"
has 'muscle.name = "brachialis";   /* muscle 1: filaments are rods 20 to 21 */'; ok $? "the second muscle's rods"
has 'joint.rod_b = 19; joint.node_b = 0;   /* forearm */'; ok $? "the elbow joins rod 19"
has 'joint.rod_a = 19; joint.node_a = 10;   /* forearm */' && has 'joint.rod_b = 22; joint.node_b = 0;   /* hand */'
ok $? "the wrist joins rods 19 and 22"
has 'bc.rod = 0;   /* humerus */'; ok $? "the clamp on the first rod is rod 0"
has 'load.rod = 22;   /* hand */'; ok $? "the force on the last rod is rod 22"

# components: a muscle per instance, named with its prefix
cat > "$tmp/comp.sinew" <<'MODEL'
material bone { E = 15 GPa; density = 1.75 g/cm^3; }
material flesh { E = 10 kPa; density = 1.06 g/cm^3; }
component limb(at) {
  bone upper { material = bone; start = at; direction = (0, 0, -1); length = 10 cm;
               radius = 5 mm; elements = 4; }
  muscle flexor { material = flesh; from = upper.start; to = at + (1, 0, -10) cm;
             radius = 3 mm; filaments = 3; sigma_max = 200 kPa; }
  clamp upper.start;
}
use left = limb((0, 1, 0) cm);
use right = limb((0, -1, 0) cm);
activate right.flexor = 1;
passive left.flexor.filament(3);
simulate { dt = 1 us; duration = 1 ms; }
MODEL
(cd "$tmp" && "$SINEWC_ASAN" comp.sinew --emit-c -o comp.c) >"$tmp/log" 2>&1; rc=$?
diag <"$tmp/log"; ok $rc "muscles in components compile"
grep -Fq 'muscle.name = "left.flexor";   /* muscle 0: filaments are rods 1 to 3 */' "$tmp/comp.c" &&
  grep -Fq 'muscle.name = "right.flexor";   /* muscle 1: filaments are rods 5 to 7 */' "$tmp/comp.c"
ok $? "each instance's muscle has the instance's prefix and its own rods"
grep -Fq 'muscle.attach_rod[0] = 4; muscle.attach_node[0] = 0;   /* right.upper */' "$tmp/comp.c"
ok $? "right.flexor is tied to right.upper, rod 4"
grep -Fq 'sw_spec_set_filament_passive(s, 0, 2) == SW_OK;   /* left.flexor, filament 3 */' "$tmp/comp.c"
ok $? "passive left.flexor.filament(3)"

# end to end: the simulator runs and writes the muscle's force
(cd "$tmp" && "$SINEWC_ASAN" arm.sinew -o arm) >"$tmp/log" 2>&1; rc=$?
diag <"$tmp/log"; ok $rc "the scene compiles to a simulator"
(cd "$tmp" && ./arm --quiet) >"$tmp/log" 2>&1; rc=$?
diag <"$tmp/log"; ok $rc "the simulator runs"
h5ls -r "$tmp/arm.h5" >"$tmp/ls" 2>&1
grep -q '^/muscles/biceps/force ' "$tmp/ls" && grep -q '^/muscles/brachialis/force ' "$tmp/ls"
ok $? "it writes /muscles/NAME/force for each muscle"
grep -q '^/rods/biceps.f18/position ' "$tmp/ls" && grep -q '^/rods/hand/position ' "$tmp/ls"
ok $? "filaments and later rods are written under their names"

# A muscle with a prescribed force (force = ...): between two clamped bones,
# once the damped filaments have settled, filament k pulls its end nodes
# together with T_k = F A_k / A, and its tie (a spring k_t) holds T_k less
# what the filament, shortened by the two ties' give, pushes back:
# T_k / (1 + 2 E A_k / (k_t L)) for a straight filament of rest length L.
cat > "$tmp/pull.sinew" <<'MODEL'
material flesh { E = 10 kPa; density = 1.06 g/cm^3; }
material bone { E = 15 GPa; density = 1.75 g/cm^3; }
bone a { material = bone; from = (0, 0, 0) cm; to = (10, 0, 0) cm; radius = 1 cm; elements = 4; }
bone b { material = bone; from = (20, 0, 0) cm; to = (30, 0, 0) cm; radius = 1 cm; elements = 4; }
clamp a.start;
clamp a.end;
clamp b.start;
clamp b.end;
signal tone(t) = 3 N * ramp(0, 1, over = 20 ms);
muscle pull {
  material = flesh;
  from = a.end;
  to = b.start;
  radius = 1 cm;
  filaments = 3;
  size_ratio = 4;
  elements = 6;
  force = tone;
  damping = 20 kg/m/s;
  attach_stiffness = 1e5 N/m;
}
simulate { dt = 3 us; duration = 0.3 s; }
output "pull.h5" every 60 ms;
MODEL
"$SINEWC" "$tmp/pull.sinew" -o "$tmp/pull" >"$tmp/out" 2>&1; ok $? "a muscle with a prescribed force compiles"
(cd "$tmp" && ./pull --quiet) >"$tmp/out" 2>&1; ok $? "it runs"
/usr/bin/python3 - "$tmp/pull.h5" <<'PY'
import sys, math, h5py
f = h5py.File(sys.argv[1], "r")
F = f["/muscles/pull/force"][-1]
A = [math.pi * 0.01**2 * 4**(k / 2) / sum(4**(j / 2) for j in range(3)) for k in range(3)]
worst = abs(F - 3.0) / 3.0
tot = 0
for k in range(3):
    j = f["/joints/pull.f%02d.end/force" % (k + 1)][-1]
    held = 3.0 * A[k] / sum(A) / (1 + 2 * 10e3 * A[k] / (1e5 * 0.1))
    worst = max(worst, abs(math.sqrt(sum(c * c for c in j)) - held) / held)
    tot += math.sqrt(sum(c * c for c in j))
print("# prescribed 3 N: muscle force %.9f N, the three ties hold %.9f N in all; largest "
      "difference from T_k / (1 + 2 E A_k / (k_t L)) %.2e" % (F, tot, worst))
sys.exit(0 if worst < 1e-9 else 1)
PY
ok $? "each filament's tie holds its share F A_k / A of the prescribed force, less the filament's push (within 1e-9)"
done_testing
