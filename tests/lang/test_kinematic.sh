#!/bin/sh
# test_kinematic.sh — joint NAME = kinematic(LEADER, FOLLOWER) in the
# generated C and in a run: the leader's element and the fraction along it
# from ROD.at(f) taken as written (between nodes), the follower's node and
# element, the reaction sent to a third point with its weight; then a bone
# turned at 20 rad/s carries a rachis, which carries a barb between its
# nodes, and the output's directors show each follower's first element with
# its leader's frame times the fixed rotation of the layout, frame by frame.
. "$(dirname "$0")/tap.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

cat > "$tmp/wing.sinew" <<'MODEL'
material bone { E = 1 GPa; density = 1000 kg/m^3; }
material keratin { E = 2.5 GPa; density = 1000 kg/m^3; }
rod ulna { material = bone; start = (0, 0, 0) m; direction = (1, 0, 0); length = 20 cm; radius = 5 mm; elements = 8; }
rod rachis { material = keratin; start = (10, 0, 0) cm; direction = (0, 1, 0); length = 10 cm; radius = 1 mm; elements = 8; }
rod barb { material = keratin; start = (10, 3, 0) cm; direction = (1, 1, 0); length = 2 cm; radius = 0.5 mm; elements = 4; }
joint base = kinematic(ulna.at(0.5), rachis.start) { stiffness = 1e4 N/m; }
joint barb_root = kinematic(rachis.at(0.3), barb.start) {
  stiffness = 1e3 N/m;
  damping = 0.01 N s/m;
  reaction = ulna.at(0.5);
  reaction_weight = 0.7;
}
angular_velocity ulna.start = (0, 0, 1) * 20 rad/s;
simulate { duration = 50 ms; }
output "wing.h5" every 5 ms { directors; positions; }
MODEL

"$SINEWC_ASAN" "$tmp/wing.sinew" --emit-c -o "$tmp/wing.c"; ok $? "a model with kinematic joints compiles to C"
grep -q 'kin.leader_rod = 0; kin.leader_elem = 4; kin.leader_xi = 0.0;' "$tmp/wing.c"
ok $? "ulna.at(0.5) of 8 elements: element 4 from its start"
grep -q 'kin.leader_rod = 1; kin.leader_elem = 2; kin.leader_xi = 0.3999999999999999;' "$tmp/wing.c"
ok $? "rachis.at(0.3) of 8 elements: 0.4 along element 2, between nodes"
grep -q 'kin.reaction_rod = 0; kin.reaction_node = 4;' "$tmp/wing.c" && grep -q 'kin.reaction_weight = 0.7;' "$tmp/wing.c"
ok $? "the barb's reaction goes to the ulna's node 4, weighted 0.7"
"$SINEWC" "$tmp/wing.sinew" -o "$tmp/wing" >/dev/null 2>&1; ok $? "it builds"
(cd "$tmp" && ./wing --quiet) >/dev/null 2>&1; ok $? "it runs"
# a tie stiff enough to bound the step: --info names its kinematic joint
sed 's|stiffness = 1e3 N/m;|stiffness = 1e8 N/m;|' "$tmp/wing.sinew" > "$tmp/stiff.sinew"
"$SINEWC" "$tmp/stiff.sinew" -o "$tmp/stiff" >/dev/null 2>&1 && "$tmp/stiff" --info > "$tmp/info" 2>&1
grep -A1 '^dt:' "$tmp/info" | grep -q "  set by kinematic joint barb_root, its tie's spring"
ok $? "--info: the step's estimate is set by the stiff tie of kinematic joint barb_root"
/usr/bin/python3 - "$tmp/wing.h5" <<'PY'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
worst, turned = 0.0, 0.0
for leader, le, follower in (("ulna", 4, "rachis"), ("rachis", 2, "barb")):
    Ql = f["/rods/%s/directors" % leader][:, le]
    Qf = f["/rods/%s/directors" % follower][:, 0]
    R = Qf[0] @ Ql[0].T
    worst = max(worst, max(np.abs(Qf[k] - R @ Ql[k]).max() for k in range(len(Ql))))
Ql = f["/rods/ulna/directors"][:, 4]
turned = np.arctan2(Ql[-1][2][1], Ql[-1][2][0])
print("# %d frames: largest |Q_follower - R Q_leader| %.2e; the ulna's element 4 turned %.3f rad"
      % (len(Ql), worst, turned))
sys.exit(0 if worst < 1e-10 and turned > 0.5 else 1)
PY
ok $? "each follower's first element keeps its leader's frame (within 1e-10) as the ulna turns"
done_testing
