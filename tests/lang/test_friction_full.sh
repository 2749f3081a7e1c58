#!/bin/sh
# test_friction_full.sh — a run whose touching pairs outgrow the friction
# anchors' table (4 rows per element in contact, contact.c) says so: N
# two-element rods crossing at one point (a star), every two touching, with
# friction.  Six spokes fit (60 pairs, 112 rows) and the run is silent;
# twenty-four do not (over 1000 pairs, 256 rows) and the run warns how many
# times a pair was left frictionless, with or without --quiet, and still
# ends normally (test_rod_friction's test_table_full counts them exactly).
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
scratch friction_full

cat > "$TMP/star.sinew" <<'SCENE'
material tissue { E = 10 MPa; density = 1 g/cm^3; }
let n = 24;
for spoke[k] in (0, n - 1) {
  rod r {
    material = tissue;
    start = (-2.5 cm * cos(k * 180 deg / n), -2.5 cm * sin(k * 180 deg / n), 0.02 mm * k);
    direction = (cos(k * 180 deg / n), sin(k * 180 deg / n), 0);
    length = 5 cm; radius = 2 mm; elements = 2;
  }
}
contact touch { rods = (spoke); stiffness = 2e3 N/m; damping = 0.05 kg/s; friction = 0.5; }
simulate { duration = 0.1 ms; }
output "star.h5" every 0.05 ms;
SCENE
for n in 6 24; do
  "$SINEWC" "$TMP/star.sinew" --let n=$n -o "$TMP/star$n" 2>"$TMP/err$n"
  ok $? "a star of $n crossed rods with friction compiles"
  diag <"$TMP/err$n"
done
"$TMP/star6" --out "$TMP/s6.h5" >"$TMP/run6" 2>&1
ok $? "six spokes run"
! grep -q "warning" "$TMP/run6"
ok $? "six spokes fit the table: no warning"
diag <"$TMP/run6"
"$TMP/star24" --quiet --out "$TMP/s24.h5" >"$TMP/run24" 2>&1
ok $? "twenty-four spokes run to the end"
grep -q "^sinew: warning: [0-9]* times a touching pair found the friction anchors' table full" "$TMP/run24"
ok $? "twenty-four spokes outgrow the table, and the run says so under --quiet"
diag <"$TMP/run24"
done_testing
