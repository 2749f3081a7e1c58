#!/bin/sh
# test_accuracy.sh — SIM --accuracy [--tolerance R] (issue 30): a run tells
# how much its answer depends on its step.
#   (a) an elastic pendulum (smooth in the step): --accuracy runs it at dt
#       into --out and at dt/2 into OUT.dt2.h5, reports each probe, the
#       hinge's angle and the objective, and finds them all within 1%; the
#       largest angle difference it reports is the one computed here from
#       the two files (h5dump), and the dt/2 file's step is half the run's;
#   (b) with a tolerance no step meets (1e-9), it halves down to dt/32 and
#       exits 5; the differences it reports shrink 4x a halving (position
#       Verlet is second order: an independent check that they measure the
#       step's error), and with 1% it stops at once with exit 0;
#   (c) the frog-like hind leg of tests/scenes/frog_leg (a new user's
#       model: rigid bones, hinges with limits, a muscle over a via point,
#       ground friction) is reported sensitive to the step, with the time
#       its runs part; its objective at both steps is printed; and it is
#       chaotic: a change of 1e-12 in a param at the same step moves its toe
#       by millimetres, which stiffer muscle tissue removes;
#   (d) misuse: a tolerance outside (0, 1), --accuracy with --restart or a
#       study.
# The measured figures are printed as TAP comments.
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
case $SINEWC in /*) ;; *) SINEWC=$ROOT/$SINEWC ;; esac   # models are compiled in $TMP
scratch accuracy
cd "$TMP" || exit 1

# the values of a dataset, one a line (h5dump, 17 digits)
vals() { h5dump -A 0 -y -w 0 -m %.17g -d "$2" "$1" | sed -n '/DATA {/,/^ *}/p' | sed '1d;$d' |
         tr ',' '\n' | grep -Eo -- '-?[0-9][0-9.e+-]*'; }
# the largest |a - b| of two such columns, in degrees (3 digits)
maxdiff_deg() { paste "$1" "$2" | awk '{d = $1 - $2; if (d < 0) d = -d; if (d > m) m = d}
                END {printf "%.3g\n", m * 180 / 3.141592653589793}'; }

cat > pend.sinew <<'EOF'
# an elastic pendulum on a hinge, released at 30 deg: smooth in the step
param release = 30 deg;
material bone { E = 1 GPa; density = 1750 kg/m^3; poisson = 0.3; }
rod bar { material = bone; start = (0, 0, 0) m; direction = (sin(release), 0, -cos(release));
          normal = (0, 1, 0); length = 0.3 m; radius = 1 cm; elements = 6; }
joint pivot = hinge(bar.start, (0, 0, 0) m) { axis = (0, 1, 0); }
gravity (0, 0, -9.81) m/s^2;
simulate { duration = 0.3 s; }
output "pend.h5" every 10 ms { probe tip = bar.end; }
maximize at(x(tip), 0.3 s);
EOF
"$SINEWC" pend.sinew -o pend 2>err
ok $? "the pendulum compiles"

# ---- (a) one comparison
./pend --accuracy --out p.h5 2>a.log
ok $? "--accuracy exits 0 on a scene that agrees at dt and dt/2"
diag < a.log
[ -f p.h5 ] && [ -f p.dt2.h5 ]
ok $? "it writes the run at dt to --out and the run at dt/2 beside it (p.dt2.h5)"
dt1=$(h5dump -A 0 -a /dt -m %.17g p.h5 | grep -Eo '\(0\): [0-9.e+-]+' | cut -d' ' -f2)
dt2=$(h5dump -A 0 -a /dt -m %.17g p.dt2.h5 | grep -Eo '\(0\): [0-9.e+-]+' | cut -d' ' -f2)
echo "# dt = $dt1 s, dt/2 = $dt2 s"
awk -v a="$dt1" -v b="$dt2" 'BEGIN {exit !(a > 0 && a == 2 * b)}'
ok $? "the second run's step is half the first's"
grep -q "pend: accuracy: dt = .* (p.h5) against dt/2 = .* (p.dt2.h5), over 31 frames:" a.log &&
  grep -q "^    probe tip: differs by up to " a.log &&
  grep -q "^    joint pivot: differs by up to .* deg, .*% of its range (.* deg)$" a.log &&
  grep -q "^    objective maximize at(x(tip), 0.3 s): .* m at dt, .* m at dt/2: differs by " a.log &&
  grep -q "pend: accuracy: all 3 observables agree within 1% of their ranges between dt and dt/2" a.log
ok $? "it reports the probe, the hinge angle and the objective, and that all three agree within 1%"
vals p.h5 /joints/pivot/angle >a1; vals p.dt2.h5 /joints/pivot/angle >a2
mine=$(maxdiff_deg a1 a2)
theirs=$(sed -n 's/^    joint pivot: differs by up to \([^ ]*\) deg.*/\1/p' a.log)
echo "# the hinge angle's largest difference: reported $theirs deg, from the files $mine deg"
[ -n "$mine" ] && [ "$mine" = "$theirs" ]
ok $? "the angle difference it reports is the files' (h5dump)"

# ---- (b) halving
./pend --accuracy --tolerance 1e-9 --duration 0.1s --out h.h5 2>b.log
ok $(( $? != 5 )) "--tolerance 1e-9, met by no step down to dt/32: exit 5"
diag < b.log
[ -f h.dt32.h5 ] && grep -q "no step down to dt/32 = .* agrees with its half within 1e-07%: the outcome is sensitive to the step" b.log
ok $? "it halves to dt/32 (h.dt32.h5) and says no step agrees"
sed -n 's/^    joint pivot: differs by up to \([^ ]*\) deg.*/\1/p' b.log >diffs
echo "# the hinge angle's differences, dt/dt2 down to dt16/dt32: $(tr '\n' ' ' <diffs)"
awk 'NR > 1 && NR <= 4 {r = prev / $1; printf "# ratio %d: %.3f\n", NR - 1, r; if (r < 3.2 || r > 4.8) bad = 1}
     {prev = $1} END {exit bad || NR != 5}' diffs >ratios
r=$?; diag <ratios
ok $r "the differences shrink 4x a halving (second order), from dt/dt2 to dt8/dt16"
./pend --accuracy --tolerance 1% --duration 0.1s --out t.h5 2>c.log
ok $? "--tolerance 1% on the smooth scene: exit 0"
grep -q "pend: accuracy: the step dt = .* is accurate to 1%: its run is t.h5 (--dt .* gives it again)" c.log &&
  [ ! -f t.dt4.h5 ]
ok $? "it names the step and its file, and runs nothing past dt/2"
diag <c.log

# ---- (c) the frog leg: sensitive
cp "$ROOT"/tests/scenes/frog_leg/*.sinew .
"$SINEWC" frog.sinew -o frog 2>err
ok $? "the frog leg compiles"
./frog --accuracy --duration 0.15s --out f.h5 2>f.log
ok $? "--accuracy on the frog leg exits with the run's code (0)"
diag <f.log
grep -q "frog: accuracy: .* of .* observables differ by more than 1% between dt and dt/2 (.*): the outcome is sensitive to the step" f.log &&
  grep -q "^    probe toe: differs by up to .*; they part at t = " f.log &&
  grep -q "^    joint right.knee_joint: differs by up to " f.log &&
  grep -q "the default step is chosen for stability, not accuracy" f.log
ok $? "it is reported sensitive to the step, with where the toe's runs part"
grep -q "^    objective maximize max_over(z(toe), 0 s, 0.25 s) - at(z(toe), 0 s): " f.log
ok $? "with its objective at both steps"

# chaos, not the step: at a fixed step, strength changed by one part in
# 10^12 moves the toe by millimetres within 0.15 s (the change grows ~10^13
# times), as halving the step does; with stiffer muscle tissue (1 MPa, the
# filaments no longer crumple under their active stress) the same change
# stays below a micrometre.  How soon the toe's runs part depends on the
# trajectory, which any change of round-off moves (0.70 mm at 0.1 s, 1.8 at
# 0.15 s and 63 at 0.25 s since the frame logarithm's series was widened;
# over 1 mm at 0.1 s before): the window is the one the --accuracy run
# above uses.
toe() { h5dump -A 0 -y -w 0 -m %.17g -d /probes/toe "$1" | sed -n '/DATA {/,/^ *}/p' | sed '1d;$d' |
        tr ',' '\n' | grep -Eo -- '-?[0-9][0-9.e+-]*' | paste - - -; }
toediff() { toe "$1" >t1; toe "$2" >t2
            paste t1 t2 | awk '{d = sqrt(($1-$4)^2 + ($2-$5)^2 + ($3-$6)^2); if (d > m) m = d}
                               END {printf "%.3g\n", m * 1000}'; }
./frog --duration 0.15s --quiet --out c0.h5 2>/dev/null
./frog --duration 0.15s --quiet --set strength=0.5000000000005 --out c1.h5 2>/dev/null
soft=$(toediff c0.h5 c1.h5)
sed 's/E = 10 kPa/E = 1 MPa/' leg.sinew >leg1.sinew && sed 's/"leg.sinew"/"leg1.sinew"/' frog.sinew >stiff.sinew &&
  "$SINEWC" stiff.sinew -o stiff 2>/dev/null
./stiff --duration 0.15s --quiet --out s0.h5 2>/dev/null
./stiff --duration 0.15s --quiet --set strength=0.5000000000005 --out s1.h5 2>/dev/null
stiff=$(toediff s0.h5 s1.h5)
echo "# strength + 1e-12 relative, same step, 0.15 s: the toe moves by up to $soft mm (10 kPa tissue), $stiff mm (1 MPa)"
awk -v a="$soft" -v b="$stiff" 'BEGIN {exit !(a > 1 && b < 1e-3)}'
ok $? "the frog leg is chaotic (a 1e-12 change moves its toe > 1 mm), and not with stiffer muscle tissue (< 1 um)"

# ---- (d) misuse
./pend --accuracy --tolerance 2 2>e1; r=$?
[ $r = 2 ] && grep -q "pend: --tolerance: expected a fraction in (0, 1) or a percentage (0.01 or 1%), got '2'" e1
ok $? "--tolerance 2 is refused (exit $r)"
./pend --out r.h5 --duration 0.05s 2>/dev/null
./pend --accuracy --restart r.h5 --duration 0.1s 2>e2; r=$?
[ $r = 2 ] && grep -q "accuracy runs the model afresh at two steps" e2
ok $? "--accuracy with --restart is refused (exit $r)"
done_testing
