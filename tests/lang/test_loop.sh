#!/bin/sh
# test_loop.sh — for NAME[VAR] in (FIRST, LAST) { items }: the items once a
# pass, each pass an instance named NAME[VAR] whose scope sees the enclosing
# one; LOOP[K].member from outside; loops nested and inside components; the
# generated scene's rods, joints and loads under those names, and a run.
. "$(dirname "$0")/tap.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

cat > "$tmp/feathers.sinew" <<'MODEL'
material keratin { E = 2.5 MPa; density = 2.5 kg/m^3; poisson = 0.5; }
component feather(base, barbs_per_side) {
  rod rachis { material = keratin; start = base; direction = (1, 0, 0); length = 200 mm;
               radius = 2 mm; elements = 8; }
  clamp rachis.start;
  for side[q] in (0, 1) {
    for barb[k] in (1, barbs_per_side) {
      let frac = k / (barbs_per_side + 1);
      rod b { material = keratin; start = rachis.at(frac); direction = (1, 2 * q - 1, 0);
              length = 30 mm; radius = 1 mm; elements = 3; }
      joint root = kinematic(rachis.at(frac), b.start) { stiffness = 1e3 N/m; }
    }
  }
}
use left = feather((0, 0, 0) m, 3);
use right = feather((0, 1, 0) m, 2);
force left.side[1].barb[3].b.end = (0, 0, 1) mN;
simulate { duration = 5 ms; }
MODEL

"$SINEWC_ASAN" --check "$tmp/feathers.sinew" 2>"$tmp/check"; ok $? "loops nested inside a component check"
grep -q 'ok: 1 file, 12 rods (46 elements), .*, 10 joints' "$tmp/check"
ok $? "2 feathers: 2 rachises and 2 x (3 + 2) barbs, each with its kinematic joint"
diag <"$tmp/check"
"$SINEWC_ASAN" "$tmp/feathers.sinew" --emit-c -o "$tmp/feathers.c"; ok $? "it compiles to C"
grep -q '"left.side\[1\].barb\[3\].b"' "$tmp/feathers.c" && grep -q '"right.side\[0\].barb\[2\].root"' "$tmp/feathers.c"
ok $? "rods and joints are named instance.loop[pass]...."
grep -q 'kin.leader_elem = 6; kin.leader_xi = 0.0;' "$tmp/feathers.c" &&
  grep -q 'kin.leader_elem = 5; kin.leader_xi = 0.33333333333333304;' "$tmp/feathers.c"
ok $? "each pass reads its own variable (3 barbs at 1/4, 1/2, 3/4 of 8 elements: nodes 2, 4, 6; 2 at 1/3, 2/3: 2.67, 5.33)"
n=$(grep -c 'sw_spec_add_load' "$tmp/feathers.c")
[ "$n" -eq 1 ] && grep -q 'load.rod = .*left.side\[1\].barb\[3\].b' "$tmp/feathers.c"
ok $? "a load on LOOP[K].member from outside reaches that pass's rod"
"$SINEWC" "$tmp/feathers.sinew" -o "$tmp/feathers" >/dev/null 2>&1 && (cd "$tmp" && ./feathers --quiet) >/dev/null 2>&1
ok $? "it runs"
"$tmp/feathers" --info > "$tmp/info" 2>&1
grep -q '^  left.side\[\*\].barb\[\*\].b: 6 rods, 3 elements, length 0.03 to 0.03 m' "$tmp/info" &&
  grep -q '^  right.side\[\*\].barb\[\*\].b: 4 rods' "$tmp/info" && grep -q '^  left.rachis: 8 elements' "$tmp/info" &&
  grep -q '^  left.side\[\*\].barb\[\*\].root: 6 joints, left.side\[\*\].barb\[\*\].b follows left.rachis, spring 1000 N/m' "$tmp/info"
ok $? "--info shows a loop's rods and kinematic joints one line a pattern (6 and 4 barbs), rods outside loops one each"
diag < "$tmp/info"

# A count that may be zero: (1, 0) is a loop of no pass, said silently, and
# what only that loop uses is not "defined but never used"; (3, 1) warns.
cat > "$tmp/count.sinew" <<'MODEL'
material keratin { E = 2.5 MPa; density = 2.5 kg/m^3; poisson = 0.5; }
let extra = 0;
let offset = (0, 2, 0) cm;
rod trunk { material = keratin; start = (0, 0, 0) m; direction = (1, 0, 0); length = 200 mm;
            radius = 2 mm; elements = 8; }
for more[k] in (1, extra) {
  rod b { material = keratin; start = trunk.end + offset; direction = (1, 0, 0);
          length = 30 mm; radius = 1 mm; elements = 3; }
}
simulate { duration = 5 ms; }
MODEL
"$SINEWC_ASAN" --check "$tmp/count.sinew" 2>"$tmp/count"; ok $? "a loop of count 0 checks"
! grep -q ': warning:' "$tmp/count"; ok $? "with no warning: neither 'no pass' nor 'offset' unused"
diag < "$tmp/count"
sed 's/let extra = 0;/let extra = 2;/' "$tmp/count.sinew" > "$tmp/count2.sinew"
"$SINEWC_ASAN" --check "$tmp/count2.sinew" 2>"$tmp/count2"
grep -q 'ok: 1 file, 3 rods' "$tmp/count2"; ok $? "with extra = 2 the loop adds its 2 rods"
sed 's/let extra = 0;/let extra = -1;/' "$tmp/count.sinew" > "$tmp/count3.sinew"
"$SINEWC_ASAN" --check "$tmp/count3.sinew" 2>"$tmp/count3"
grep -q "warning: loop 'more' runs from 1 to -1: no pass" "$tmp/count3"; ok $? "(1, -1) still warns"
done_testing
