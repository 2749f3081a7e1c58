#!/bin/sh
# test_objective.sh — the problem in the model, from the language to the
# simulator's report:
#
#   a rigid bar dropped from z0 (a param with a range) falls as
#   z(t) = z0 - g t^2 / 2, which position Verlet follows exactly at its
#   steps; `maximize at(z(centre), 0.25 s) - 0 cm` with the penalty
#   weight * (max_over - min_over) over [0.1 s, 0.3 s] has the closed forms
#   objective = z(0.25 s), penalty = weight * (z(0.1 s) - z(0.3 s)), score =
#   objective - penalty: the line SIM prints at its end (in cm, the unit the
#   model wrote for a length) and the root attributes of its HDF5 (SI) are
#   checked against them, and again with --set z0=2.5m;
#   `minimize mean_over(...)` gives the trapezoidal time average, exact
#   for a quadratic up to its error term -g h^2 / 12, and score =
#   -(objective + penalty);
#   --info and --help list the ranges and the objective; --quiet prints no
#   objective; a run cut short (--duration) says "not reached", exits 0
#   and stores NaN; one continued with --restart inside a window stores
#   the uninterrupted run's bits; penalties in a component's instances add
#   up; the generated C carries objective() with a #line back to each
#   statement.
#
# python3-h5py is installed by `make test` (scripts/deps.sh).
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
SC=$SINEWC_CHECK
PY=/usr/bin/python3
scratch objective

cat >"$TMP/fall.sinew" <<'EOF'
# a rigid bar dropped from rest
param z0 = 2 m in (1 m, 3 m);
param weight = 0.5 in (0, 1);
material steel { E = 200 GPa; density = 7.8 g/cm^3; }
rod bar { material = steel; start = (0 m, 0 m, z0); direction = (1, 0, 0); normal = (0, 0, 1); length = 10 cm; radius = 1 cm; elements = 4; rigid = true; }
gravity (0, 0, -9.81) m/s^2;
simulate { duration = 0.4 s; dt = 1 ms; }
output "fall.h5" every 10 ms { probe centre = centre_of_mass(bar); }
maximize at(z(centre), 0.25 s) - 0 cm;
penalty weight * (max_over(z(centre), 0.1 s, 0.3 s) - min_over(z(centre), 0.1 s, 0.3 s));
EOF

"$SC" "$TMP/fall.sinew" -o "$TMP/fall" 2>"$TMP/err"; ok $? "the falling bar compiles"
diag <"$TMP/err"

# closed forms, in m: objective, penalty, score
expected() {   # expected Z0 WEIGHT
  awk -v z0="$1" -v w="$2" 'BEGIN { g = 9.81
    o = z0 - g * 0.25^2 / 2; p = w * g * (0.3^2 - 0.1^2) / 2
    printf "%.12g %.12g %.12g\n", o, p, o - p }'
}
# the printed line: "fall: objective: maximize ... = V cm; penalty P cm; score S cm"
printed() {
  sed -n 's/^fall: objective: .* = \([^ ]*\) cm; penalty \([^ ]*\) cm; score \([^ ]*\) cm$/\1 \2 \3/p' "$1"
}
# |a_i - b_i * scale| <= tol for the three figures; prints them
close() {   # close "A1 A2 A3" "B1 B2 B3" SCALE TOL WHAT
  echo "$1 $2" | awk -v k="$3" -v tol="$4" -v what="$5" '{
    bad = 0
    for (i = 1; i <= 3; i++) { e = $i - $(i + 3) * k; if (e < 0) e = -e; if (e > tol) bad = 1
      printf "# %s: %s = %s (closed form %.12g, error %.3g)\n", what,
             i == 1 ? "objective" : i == 2 ? "penalty" : "score", $i, $(i + 3) * k, e }
    exit bad }'
}
stored() {   # stored FILE: objective penalty score units text
  $PY - "$1" <<'EOF'
import sys, h5py
with h5py.File(sys.argv[1], "r") as f:
    a = f.attrs
    def s(x): return x.decode() if isinstance(x, bytes) else str(x)
    print("%.17g %.17g %.17g" % (a["objective"], a["penalty"], a["score"]))
    print(s(a["objective_units"]))
    print(s(a["objective_text"]))
EOF
}

(cd "$TMP" && ./fall --out "$TMP/a.h5") 2>"$TMP/run"; rc=$?
ok $rc "a run with an objective exits 0 (exit $rc)"
got=$(printed "$TMP/run")
[ -n "$got" ]; ok $? "it prints objective, penalty and score at its end, in cm"
[ -n "$got" ] || diag <"$TMP/run"
close "$got" "$(expected 2 0.5)" 100 1e-6 "printed"; ok $? "the printed figures are the closed forms (to 1e-6 cm, the 9 digits printed)"
stored "$TMP/a.h5" >"$TMP/attrs"; ok $? "the HDF5 root has objective, penalty, score, objective_units, objective_text"
close "$(sed -n 1p "$TMP/attrs")" "$(expected 2 0.5)" 1 1e-12 "stored"; ok $? "the stored figures are the closed forms in SI (to 1e-12 m)"
[ "$(sed -n 2p "$TMP/attrs")" = m ]; ok $? "objective_units is the SI unit, m"
[ "$(sed -n 3p "$TMP/attrs")" = "maximize at(z(centre), 0.25 s) - 0 cm" ]
ok $? "objective_text is the statement as written"

(cd "$TMP" && ./fall --set z0=2.5m --out "$TMP/b.h5") 2>"$TMP/run"
got=$(printed "$TMP/run")
close "$got" "$(expected 2.5 0.5)" 100 1e-6 "--set"; ok $? "--set z0=2.5m moves the objective with it"
(cd "$TMP" && ./fall --set weight=0 --out "$TMP/c.h5") 2>"$TMP/run"
got=$(printed "$TMP/run")
close "$got" "$(expected 2 0)" 100 1e-6 "--set weight=0"; ok $? "--set weight=0: no penalty, score = objective"

# --quiet: nothing; a run cut short: not reached, exit 0, NaN stored
(cd "$TMP" && ./fall --quiet --out "$TMP/q.h5") 2>"$TMP/run"; rc=$?
[ $rc -eq 0 ] && ! [ -s "$TMP/run" ]; ok $? "--quiet prints no objective (exit $rc)"
(cd "$TMP" && ./fall --duration 0.2s --out "$TMP/s.h5") 2>"$TMP/run"; rc=$?
ok $rc "a run shorter than the objective's times exits 0 (exit $rc)"
grep -q '^fall: objective: maximize at(z(centre), 0.25 s) - 0 cm: not reached (at(z(centre), 0.25 s): the run ended before t = 0.25 s)$' "$TMP/run"
ok $? "and says the objective was not reached, and why"
diag <"$TMP/run"
stored "$TMP/s.h5" | sed -n 1p | grep -q '^nan nan nan$'; ok $? "its file stores NaN for the three"

# --info and --help
"$TMP/fall" --info >"$TMP/info"
grep -q '^  z0 = 2 m in (1 m, 3 m)$' "$TMP/info" && grep -q '^  weight = 0.5 in (0, 1)$' "$TMP/info"
ok $? "--info lists each param with its range"
grep -q '^objective: maximize at(z(centre), 0.25 s) - 0 cm  # fall.sinew:9$' "$TMP/info" &&
  grep -q '^  shown in cm; 1 penalty; score = objective - penalties$' "$TMP/info"
ok $? "--info shows the objective, its unit and its penalties"
sed -n '/^params:/,$p' "$TMP/info" | diag
"$TMP/fall" --help >"$TMP/help"
grep -Eq '^  z0 +=  *2 m +in \(1 m, 3 m\) +length \(m\) +fall.sinew:2$' "$TMP/help"
ok $? "--help lists the ranges"
grep -q '^objective: maximize' "$TMP/help"; ok $? "--help shows the objective"

# minimize the trapezoidal mean
sed 's/^maximize .*/minimize mean_over(z(centre), 0.1 s, 0.3 s);/' "$TMP/fall.sinew" >"$TMP/low.sinew"
"$SC" "$TMP/low.sinew" -o "$TMP/low" 2>"$TMP/err"; ok $? "a model that minimizes a mean compiles"
diag <"$TMP/err"
(cd "$TMP" && ./low --out "$TMP/l.h5") 2>"$TMP/run"
got=$(sed -n 's/^low: objective: .* = \([^ ]*\) m; penalty \([^ ]*\) m; score \([^ ]*\) m$/\1 \2 \3/p' "$TMP/run")
want=$(awk 'BEGIN { g = 9.81; z0 = 2; h = 1e-3
  m = z0 - g * (0.3^3 - 0.1^3) / (6 * 0.2) - g * h^2 / 12; p = 0.5 * g * (0.3^2 - 0.1^2) / 2
  printf "%.12g %.12g %.12g\n", m, p, -(m + p) }')
close "$got" "$want" 1 1e-8 "minimize, printed"; ok $? "minimize: the trapezoidal mean, and score = -(objective + penalty), in m (no length unit written)"
close "$(stored "$TMP/l.h5" | sed -n 1p)" "$want" 1 1e-12 "minimize, stored"
ok $? "the stored mean is the trapezoidal rule's to 1e-12 m (its error term g h^2/12 is 8.2e-7 m)"

# a penalty in a component: one per instance, each with its own weight
sed 's/^penalty .*/component drag(k) { penalty k * at(z(centre), 0.1 s); }\
use a = drag(0.25);\
use b = drag(0.5);/' "$TMP/fall.sinew" >"$TMP/comp.sinew"
"$SC" "$TMP/comp.sinew" -o "$TMP/comp" 2>"$TMP/err"; ok $? "penalties in a component's instances compile"
diag <"$TMP/err"
(cd "$TMP" && ./comp --out "$TMP/k.h5") 2>"$TMP/run"
got=$(sed -n 's/^comp: objective: .* = \([^ ]*\) cm; penalty \([^ ]*\) cm; score \([^ ]*\) cm$/\1 \2 \3/p' "$TMP/run")
want=$(awk 'BEGIN { g = 9.81; o = 2 - g * 0.25^2 / 2; p = 0.75 * (2 - g * 0.1^2 / 2)
  printf "%.12g %.12g %.12g\n", o, p, o - p }')
close "$got" "$want" 100 1e-6 "two instances"; ok $? "their penalties add up: (0.25 + 0.5) z(0.1 s)"

# continued with --restart from t = 0.2 s, inside the window [0.1 s, 0.3 s]:
# the window's extremes and trapezoidal sum carry on, to the uninterrupted
# run's bits
(cd "$TMP" && ./low --duration 0.4s --out "$TMP/whole.h5" --quiet) 2>/dev/null
(cd "$TMP" && ./low --duration 0.2s --out "$TMP/r.h5" --quiet) 2>/dev/null
(cd "$TMP" && ./low --restart "$TMP/r.h5" --duration 0.4s) 2>"$TMP/run"; rc=$?
ok $rc "a run continued with --restart exits 0 (exit $rc)"
grep -q "^low: objective: minimize mean_over" "$TMP/run"; ok $? "and prints the objective"
[ "$(stored "$TMP/r.h5" | sed -n 1p)" = "$(stored "$TMP/whole.h5" | sed -n 1p)" ]
ok $? "whose figures are an uninterrupted run's, to the bit ($(stored "$TMP/r.h5" | sed -n 1p))"

# the generated C
"$SC" "$TMP/fall.sinew" --emit-c -o "$TMP/fall.c" 2>/dev/null
grep -q '^static void objective(const double \*P, const double \*R, double \*value, double \*penalty) {$' "$TMP/fall.c" &&
  grep -q '^#line 9 "fall.sinew"$' "$TMP/fall.c" && grep -q '^#line 10 "fall.sinew"$' "$TMP/fall.c" &&
  grep -q '^  \*penalty += (P\[1\] \* (R\[1\] - R\[2\]));$' "$TMP/fall.c"
ok $? "the generated C has objective(), a #line for each statement, and params and reductions as P[] and R[]"
grep -q '{"z0", 2.0, {0, 1, 0, 0}, "m", "fall.sinew:2", 1, 1.0, 3.0}' "$TMP/fall.c"
ok $? "and the params' ranges in its table"

done_testing
