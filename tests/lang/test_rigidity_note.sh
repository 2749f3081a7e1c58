#!/bin/sh
# test_rigidity_note.sh — after a run the simulator names the elastic rods
# that kept their rest shape within 0.01 (largest stretch or shear strain,
# largest bend end to end; engine/rigidity.c, sim/cli_rigidity.c): a stiff
# bone and a soft strand, each clamped at one end and released horizontal
# under gravity.  The bone is named, with its explicit step (its elastic
# waves set the scene's), the strand (which sags) is not, and --quiet
# prints no note.  The bone's bend is checked against the cantilever's:
# its static tip slope under its weight is theta = q L^3 / (6 E I) =
# (2/3) rho g L^3 / (E r^2) = 6.10e-5 rad; released from rest, a load
# applied at once swings a linear beam to twice its static deflection, so
# the largest bend over the frames (every 1 ms, the first mode's period
# about 4.9 ms) lies between 1.5 and 2.05 times theta, at the default
# step and at 0.5 us.  A passive muscle of three filaments with free ends
# falls beside them: under uniform gravity its filaments move alike, and a
# second note names it.
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
case $SINEWC in /*) ;; *) SINEWC=$ROOT/$SINEWC ;; esac   # the scene is compiled in $TMP
scratch rigidity
cd "$TMP" || exit 1
cat >r.sinew <<'SCENE'
material stiff { E = 15 GPa; density = 1.75 g/cm^3; poisson = 0.5; }
material soft { E = 20 kPa; density = 1 g/cm^3; poisson = 0.5; }
bone femur { material = stiff; start = (0, 0, 0) m; direction = (1, 0, 0); normal = (0, 0, 1);
             length = 0.2 m; radius = 10 mm; elements = 10; }
rod strand { material = soft; start = (0, 0.1, 0) m; direction = (1, 0, 0); normal = (0, 0, 1);
             length = 0.2 m; radius = 2 mm; elements = 10; }
muscle band { material = soft; from = (0, 0.3, 0) m; to = (0.2, 0.3, 0) m; radius = 5 mm;
               filaments = 3; sigma_max = 100 kPa; elements = 6; }
clamp femur.start;
clamp strand.start;
gravity (0, 0, -9.81) m/s^2;
simulate { duration = 20 ms; }
output "r.h5" every 1 ms;
SCENE
"$SINEWC" r.sinew -o r 2>err; ok $? "the scene compiles"
diag <err
./r 2>log; ok $? "it runs"
note=$(grep ': note: .* kept .* rest shape' log)
echo "$note" | diag
echo "$note" | grep -q "1 rod kept its rest shape within 0.01 over the 21 frames"
ok $? "one rod is named, over the run's 21 frames"
echo "$note" | grep -q " femur ([^)]*; its elastic waves set the explicit step"
ok $? "the bone, whose elastic waves set the scene's step"
! echo "$note" | grep -q "strand"
ok $? "not the soft strand, which sags"
bend=$(echo "$note" | sed 's/.* femur ([^,]*, \([^ ]*\) rad.*/\1/')
awk -v b="$bend" 'BEGIN { t = 2.0 / 3.0 * 1750 * 9.81 * 0.2^3 / (15e9 * 0.01^2);
  printf "# femur: largest bend %s rad, %.3f x the static tip slope %.4g rad\n", b, b / t, t;
  exit !(b >= 1.5 * t && b <= 2.05 * t) }'
ok $? "the bone's largest bend is 1.5-2.05 x its static tip slope"
# at a quarter of the default step (half the estimate, 1.81 us): the same bracket
./r --dt 0.5us --out half.h5 2>hlog; ok $? "it runs at dt = 0.5 us"
hbend=$(grep ': note: .* kept .* rest shape' hlog | sed 's/.* femur ([^,]*, \([^ ]*\) rad.*/\1/')
awk -v b="$hbend" -v b1="$bend" 'BEGIN { t = 2.0 / 3.0 * 1750 * 9.81 * 0.2^3 / (15e9 * 0.01^2);
  printf "# femur at 0.5 us: largest bend %s rad (%s at dt), %.3f x the static tip slope\n", b, b1, b / t;
  exit !(b >= 1.5 * t && b <= 2.05 * t) }'
ok $? "at 0.5 us too"
mnote=$(grep ': note: the filaments of .* moved alike' log)
echo "$mnote" | diag
echo "$mnote" | grep -q "the filaments of 1 muscle moved alike within 0.01 .* band (3 filaments, "
ok $? "the falling muscle's filaments are named as moving alike"
./r --quiet 2>qlog; ok $? "a quiet run"
! grep -q "note:" qlog
ok $? "--quiet prints no note"
done_testing
