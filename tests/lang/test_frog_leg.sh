#!/bin/sh
# test_frog_leg.sh — a new user's frog leg (tests/scenes/frog_leg, issue 30):
# a knee extensor of 3 soft filaments (E = 10 kPa) over a via point, at an
# active stress up to 30 times E.
#
#   As written, its muscle takes the variational law (the default for
#   muscles) and the run completes, at strength 1, at the default step
#   (5.13 us) and at 2.5 us: no instability, every frame to 0.25 s.  Its
#   figures are not asserted: the scene is chaotic (README.md there).
#
#   With the reference law stated (`variational = false` on its material),
#   a run below the stable estimate goes unstable as the user's did (at
#   4 us; here 3 us, see below), and the report says why: how short the
#   filament was squeezed,
#   what Gazzola's law does there, the stable dt at that length (above dt,
#   the step not the cause, or below it, brought down by that law's
#   stiffening: the run is chaotic and either happens), and the way out.  The same law fails at
#   strength 1 at the default step.
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
scratch frog_leg
cp tests/scenes/frog_leg/frog.sinew tests/scenes/frog_leg/leg.sinew "$TMP/"

# the run's end: exit status, the simulator's own stderr, and the last frame
last_time() {
  /usr/bin/python3 -c 'import h5py, sys; print("%.6g" % h5py.File(sys.argv[1], "r")["/time"][-1])' "$1" 2>/dev/null
}

"$SINEWC" "$TMP/frog.sinew" -o "$TMP/frog" 2>"$TMP/err"; ok $? "the frog builds as written"
diag <"$TMP/err"
"$TMP/frog" --info >"$TMP/info" 2>&1
grep -q '^constitutive law: variational (loads the gradient of the elastic energy) on 3 of 3 elastic rods: right.extensor.f01, right.extensor.f02, right.extensor.f03$' "$TMP/info"
ok $? "its extensor's filaments take the variational law (a muscle's default)"
grep '^constitutive law\|^dt:' "$TMP/info" | diag

for dt in default 2.5us; do
  opt=""
  [ "$dt" = default ] || opt="--dt $dt"
  (cd "$TMP" && ./frog --quiet --set strength=1 $opt --out "s1_$dt.h5") >"$TMP/run" 2>&1; rc=$?
  # 0, or 5 when one of the user's expect lines misses (chaotic figures)
  [ "$rc" -eq 0 ] || [ "$rc" -eq 5 ]; ok $? "strength 1, dt $dt: the run completes (exit $rc, not 3)"
  ! grep -q unstable "$TMP/run"; ok $? "strength 1, dt $dt: nothing became unstable"
  [ "$(last_time "$TMP/s1_$dt.h5")" = 0.25 ]; ok $? "strength 1, dt $dt: frames to t = 0.25 s (last $(last_time "$TMP/s1_$dt.h5") s)"
  grep -v '^frog: \(passed\|expectations\)\|^    ' "$TMP/run" | diag
done

# ---- the reference law, stated: the user's failure and its report
mkdir "$TMP/ref"
cp "$TMP/frog.sinew" "$TMP/ref/"
sed 's/^material muscle_tissue { \(.*\) }$/material muscle_tissue { \1 variational = false; }/' \
  "$TMP/leg.sinew" >"$TMP/ref/leg.sinew"
grep -q '^material muscle_tissue { .* variational = false; }$' "$TMP/ref/leg.sinew"
ok $? "the reference law stated on the muscle's material"
"$SINEWC" "$TMP/ref/frog.sinew" -o "$TMP/ref/frog" 2>"$TMP/err"; ok $? "it builds"
"$TMP/ref/frog" --info | grep -q '^constitutive law: Gazzola et al. 2018 .*, all 3 elastic rods$'
ok $? "its filaments take Gazzola et al. 2018's law"

# The user's run was at 4 us.  Since the joints from the bones to the
# filaments' ends are implicit under imex (issue 31), the run at exactly
# 4 us happens to reach the end (the scene is chaotic: README.md there);
# at 3 us and 5 us it fails as before, the filament squeezed to under 1%.
(cd "$TMP/ref" && ./frog --quiet --dt 3us --out ref.h5) >"$TMP/run" 2>&1; rc=$?
[ "$rc" -eq 3 ]; ok $? "dt = 3 us: unstable (exit $rc), as the user saw at 4 us"
diag <"$TMP/run"
msg=$(grep '^sinew: ' "$TMP/run")
has() { printf '%s\n' "$msg" | grep -q -- "$1"; }
has "rod 'right.extensor.f0[123]' became unstable at element [0-9]*, t = [0-9.]* s: "
ok $? "the report names the filament, the element and the time"
has "; dt = 3e-06 s, stable dt estimate 1.03e-05 s\. As dt is below the estimate, the rest state does not explain it: "
ok $? "it says that dt is below the estimate"
has "the rod had shortened to [0-9.e+-]*% of its rest length (element [0-9]*, t = [0-9.]* s)"
ok $? "it says how short the filament was squeezed, where and when"
has "where Gazzola et al. 2018's law (n = S^ s / e, c = B^ k / eps^3) pushes back with [0-9.e+]* times E A and is [0-9.e+]* times as stiff in stretch as at rest"
ok $? "it names Gazzola's law and what it does at that length"
# where the filament was squeezed furthest its own stable dt is above dt
# (the step is not the cause) or, squeezed further, below it (the law's
# stiffening brought it down); which one depends on the chaotic run (below
# 1 % of its length at 3 us either way), and the report says which
has "; the rod's stable dt at that length is [0-9.e+-]* s ([0-9.e+-]* s at rest), \(still above dt, so the step is not the cause\|and dt is above it\)"
ok $? "it gives the stable dt at that length and how it compares with dt"
has '\. The variational law (`variational = true` on its material, the default for muscles)'
ok $? "it names the way out"
# the figures: squeezed below 5 %, stiffer by over 400 (1/e^2), a stable dt
# at that length below the rest one, and on the side of dt the words say
above=0; has "still above dt, so the step is not the cause" && above=1
printf '%s\n' "$msg" | sed 's/.*shortened to \([0-9.e+-]*\)% .* is \([0-9.]*\) times as stiff.* length is \([0-9.e+-]*\) s (\([0-9.e+-]*\) s at rest).*/\1 \2 \3 \4/' |
  awk -v above=$above '{ exit !($1 < 5 && $2 > 400 && $3 < $4 && (above ? $3 > 3e-6 : $3 < 3e-6)) }'
ok $? "its figures: under 5 % of the rest length, over 400 times as stiff, dt at that length below dt at rest and on the side of 3 us the report says"

(cd "$TMP/ref" && ./frog --quiet --set strength=1 --out ref1.h5) >"$TMP/run" 2>&1; rc=$?
[ "$rc" -eq 3 ] && grep -q 'the rod had shortened to ' "$TMP/run"
ok $? "strength 1 at the default step: unstable as well (exit $rc), explained the same way"
done_testing
