#!/bin/sh
# test_param_at.sh — ROD.at(param): a param moves the points a joint and a
# muscle hold.  The simulator computes their nodes and the rods laid from them
# when it builds the scene (derive() in the C), so `--set f=V` must give the
# same run, bit for bit, as the model compiled with f a let set to V; a
# value that puts a node off its rod is refused with the joint's name.
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
SINEWC=$(cd "$(dirname "$SINEWC")" && pwd)/$(basename "$SINEWC")   # the runs are made in $TMP
SINEWC_CHECK=$(cd "$(dirname "$SINEWC_CHECK")" && pwd)/$(basename "$SINEWC_CHECK")
scratch param-at
cd "$TMP" || exit 1
cat > m.sinew <<'EOF'
param f = 0.3 in (0.1, 0.9);
material stiff { E = 20 MPa; density = 1000 kg/m^3; }
material soft { E = 10 kPa; density = 1000 kg/m^3; }
rod beam { material = stiff; start = (0, 0, 0) m; direction = (1, 0, 0);
           length = 1 m; radius = 2 cm; elements = 20; }
let fa = round(f * 20) / 20;          # on a node of the beam
rod arm { material = stiff; from = beam.at(fa); to = beam.at(fa) + (0, 0.2, 0) m;
          radius = 1 cm; elements = 4; }
joint weld = fixed(arm.start, beam.at(fa));
muscle flexor { material = soft; from = arm.end; to = beam.at(fa + 0.3); radius = 5 mm;
                filaments = 1; elements = 4; sigma_max = 1 MPa; }
activate flexor = 0.5;
clamp beam.start;
gravity (0, 0, -9.81) m/s^2;
simulate { dt = 10 us; duration = 20 ms; }
output "m.h5" every 1 ms { probe tip = beam.end; }
EOF
sed 's/^param f = 0.3 in (0.1, 0.9);/let f = 0.3;/' m.sinew > l.sinew

"$SINEWC_CHECK" m.sinew --emit-c -o m.c 2> err; ok $? "a model whose joint and muscle stand at ROD.at(param) compiles"
diag < err
grep -q 'joint.node_b = (int)lround(D\[0\] \* 20); /\* 6 at the defaults \*/' m.c
ok $? "the joint's node is computed from the param when the scene is built"
grep -q 'muscle.attach_node\[1\] = (int)lround((D\[0\] + 0.3) \* 20);' m.c
ok $? "so is the muscle's end"
grep -q '^  D\[0\] = (round((P\[0\] \* 20.0)) / 20.0);   /\* let fa \*/' m.c
ok $? "derive() computes the let once, named"
"$SINEWC" m.sinew -o m > /dev/null 2>&1; ok $? "the simulator builds"

for v in 0.55 0.12 0.3; do
  "$SINEWC" l.sinew --let f=$v -o l > /dev/null 2>&1 || echo "let build failed" | diag
  ./l --quiet --out l.h5 > /dev/null 2>&1
  ./m --quiet --set f=$v --out m.h5 --compare l.h5 --rtol 0 > cmp 2>&1
  ok $? "--set f=$v runs bit for bit as the model compiled with f = $v"
  tail -1 cmp | diag
done
# a different f is a different scene (the check above is not vacuous)
./m --quiet --set f=0.55 --out m55.h5 > /dev/null 2>&1
./m --quiet --out m30.h5 --compare m55.h5 --rtol 0 > cmp 2>&1
[ $? -ne 0 ] && grep -q 'rods/arm/position' cmp
ok $? "f = 0.3 and f = 0.55 place the arm differently"

./m --quiet --set f=1.2 --out bad.h5 > out 2> err
rc=$?
ok "$([ "$rc" -ne 0 ] && [ "$rc" -lt 128 ]; echo $?)" "a node off the rod fails cleanly (exit $rc)"
grep -q "joint 'flexor.f01.end': node_b 30 out of range for rod 'beam'" err
ok $? "and names the joint, the node and the rod"
diag < err

# a negative default keeps its unit in --help and in a study file (the
# muscular snake's phases, -180 deg, were shown in radians)
cat > neg.sinew <<'EOF'
param phase = -180.0 deg in (-180 deg, 180 deg);
material stiff { E = 20 MPa; density = 1000 kg/m^3; }
rod r { material = stiff; start = (0, 0, 0) m; direction = (1, 0, 0); length = 1 m;
        radius = 1 cm; elements = 4; }
torque r.end = (1, 0, 0) * sine(1 mN m, 1 Hz, phase = phase);
simulate { duration = 1 ms; }
EOF
"$SINEWC" neg.sinew -o neg > /dev/null 2>&1
./neg --help | grep -q '^  phase = -180 deg  *in (-180 deg, 180 deg)'
ok $? "a negative default is shown in its own unit (-180 deg)"
./neg --help | grep '^  phase' | diag
done_testing
