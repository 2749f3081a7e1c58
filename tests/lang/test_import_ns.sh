#!/bin/sh
# test_import_ns.sh — imports that compose (import "FILE" as NAME;):
#
#   two libraries that both define 'bone_tissue' used in one scene, one
#   under a namespace: two cantilevers of the same geometry, one of each
#   material, sag under their weight by w L^4 / (8 E I), so the ratio of
#   their tip deflections is (rho_a / E_a) / (rho_b / E_b) (asserted to 1%);
#   a finger component used twice from the namespace gives rods and joints
#   of distinct names (index.proximal, little.proximal); the runnable scene
#   imported for its definitions adds none of its statements (no 'alone'
#   instance, no gravity of its own, its output file not used); the source
#   stored in the simulator holds the imported file once; the plain import
#   of both libraries instead is an error that names both files.
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
SC=$SINEWC_CHECK
scratch importns
cp -r examples/constructs/lib "$TMP/lib"

cat >"$TMP/sag.sinew" <<'EOF'
import "lib/tissues.sinew";              # bone_tissue: 5 MPa, 1.75 g/cm^3
import "lib/finger.sinew" as finger;     # finger.bone_tissue: 20 MPa, 1.9 g/cm^3
use index = finger.finger((0, 0, 0) m);
use little = finger.finger((0, 0.03, 0) m, scale = 0.7);
rod stiff { material = finger.bone_tissue; start = (0, 0.06, 0) m; direction = (1, 0, 0);
            normal = (0, 0, 1); length = 5 cm; radius = 3 mm; elements = 20; damping = 2 kg/m/s; }
rod soft { material = bone_tissue; start = (0, 0.09, 0) m; direction = (1, 0, 0);
           normal = (0, 0, 1); length = 5 cm; radius = 3 mm; elements = 20; damping = 2 kg/m/s; }
clamp stiff.start;
clamp soft.start;
simulate { duration = 0.5 s; }
output "sag.h5" every 0.1 s;
gravity (0, 0, -9.81) m/s^2;
EOF
cd "$TMP" || exit 1
"$SC" sag.sinew -o sag 2>err; ok $? "two libraries both defining bone_tissue, one as a namespace, compile"
diag <err
./sag --info >info 2>&1
grep -q '^  index.proximal: ' info && grep -q '^  little.proximal: ' info && grep -q '^  index.middle: hinge' info
ok $? "the component used twice from the namespace: rods and joints named by instance"
grep -q 'alone' info; ok $((! $?)) "the imported scene's own 'use alone' is not in the scene"
grep -q '^rods: 6 ' info; ok $? "six rods: two fingers and the two cantilevers"
grep -q '^output: sag.h5 ' info; ok $? "the output is the importer's, not finger.h5"
grep -Eq '^boundary conditions: 4 .*4 clamped' info; ok $? "4 clamps: the two fingers' and the cantilevers' (not the imported scene's)"
diag <info
./sag --quiet 2>err; ok $? "it runs"
/usr/bin/python3 - sag.h5 >out 2>&1 <<'EOF'
import sys, h5py
f = h5py.File(sys.argv[1], "r")
tip = lambda r: -f["rods/%s/position" % r][-1, -1, 2]
d_stiff, d_soft = tip("stiff"), tip("soft")
E = {"stiff": 20e6, "soft": 5e6}
rho = {"stiff": 1900.0, "soft": 1750.0}
want = (rho["stiff"] / E["stiff"]) / (rho["soft"] / E["soft"])
print("tip deflections: finger.bone_tissue %.4g m, bone_tissue %.4g m" % (d_stiff, d_soft))
print("ratio %.5f, (rho/E) ratio %.5f, relative error %.2e" % (d_stiff / d_soft, want,
                                                            abs(d_stiff / d_soft / want - 1)))
a = f["rods/stiff"].attrs["material"], f["rods/soft"].attrs["material"]
print("materials:", a)
sys.exit(0 if abs(d_stiff / d_soft / want - 1) < 0.01 and a == ("finger.bone_tissue", "bone_tissue")
         else 1)
EOF
ok $? "each rod sags as its own material says (w L^4 / (8 E I) ratio, 1%)"
diag <out
cat >twice.sinew <<'EOF'
import "lib/finger.sinew" as a;
import "lib/finger.sinew" as b;
use one = a.finger((0, 0, 0) m);
use two = b.finger((0, 0.05, 0) m);
EOF
"$SC" twice.sinew --emit-c -o twice.c 2>err
n=$(grep -c 'imported: lib/finger.sinew' twice.c)
ok $((n != 1)) "a file imported under two namespaces is in the model source once ($n)"

# the same two libraries imported plainly: one scope, two bone_tissue
cat >plain.sinew <<'EOF'
import "lib/tissues.sinew";
import "lib/finger.sinew";
EOF
"$SC" --check plain.sinew >out 2>&1; rc=$?
ok $((rc != 1)) "importing both plainly is an error (exit $rc)"
grep -q "^lib/finger.sinew:6:1: error: 'bone_tissue' is already defined (as a material at lib/tissues.sinew:3)" out
ok $? "naming the file and line of each definition"
diag <out
done_testing
