#!/bin/sh
# test_restart.sh — SIM --restart RUN.h5 continues a run from its file and
# gives the datasets of a run that never stopped, bit for bit (h5diff finds
# no difference, and --compare with --rtol 0 agrees):
#
#   a run of 0.1 s continued to 0.2 s; a run stopped with Ctrl-C (SIGINT)
#   part way and continued with no other argument, its expectations (which
#   span the whole run) then passing as in one run; a file of another model,
#   another param or dt is refused (exit 4) naming what differs; a file that
#   already reaches the duration, and --out naming another file, are usage
#   errors (exit 2); a run of implicit rods, whose kicks keep their
#   factorisations over several steps (rod_implicit.c), continued from its
#   file, gives the uninterrupted run's datasets to the bit; the file's
#   integrator is taken when none is given, and another one is refused; a
#   run whose holds let go (until) continued from before and after a release;
#   a rope held on a post by friction, whose anchors are state, continued
#   likewise gives the uninterrupted run's datasets to the bit, and so do
#   two sticks on two bars, one held by rod-rod friction and one sliding.
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
SC=$SINEWC_CHECK
scratch restart

"$SC" examples/pendulum.sinew -o "$TMP/p" 2>"$TMP/err"; ok $? "the pendulum compiles"
diag <"$TMP/err"
cd "$TMP" || exit 1

# 1. a finished run, extended
./p --duration 0.2s --out full.h5 --quiet 2>err; ok $? "an uninterrupted run of 0.2 s"
./p --duration 0.1s --out part.h5 --quiet 2>err; ok $? "a run of 0.1 s"
./p --restart part.h5 --duration 0.2s >run 2>&1; rc=$?
ok $rc "continued to 0.2 s (exit $rc; the pendulum's expectations lie later, not reached)"
grep -q '^p: continuing part.h5 from t = 0.1 s (frame 101)$' run; ok $? "it says where it continues from"
diag <run
h5diff part.h5 full.h5 >diff 2>&1; ok $? "every dataset equals the uninterrupted run's (h5diff)"
diag <diff
./p --duration 0.1s --out part2.h5 --quiet 2>err
./p --restart part2.h5 --duration 0.2s --compare full.h5 --rtol 0 --quiet >run 2>&1; rc=$?
grep -q 'compare: [0-9]* datasets match, 0 differ$' run; ok $? "--compare --rtol 0 agrees (exit $rc)"
diag <run

# 2. stopped by Ctrl-C part way, continued with no other argument
./p --duration 3s --out long.h5 --quiet 2>err; ok $? "an uninterrupted run of 3 s"
./p --duration 3s --out cut.h5 --quiet 2>err &
pid=$!
sleep 1
kill -INT $pid
wait $pid; rc=$?
ok $((rc != 130)) "a run of 3 s stopped by SIGINT (exit $rc)"
/usr/bin/python3 -c "
import h5py; f = h5py.File('cut.h5', 'r')
print('stopped at t = %.6g s, frame %d; status: %s' % (f['time'][-1], len(f['time']), f.attrs['status']))
" | diag
./p --restart cut.h5 --duration 3s >run 2>&1; rc=$?
ok $rc "continued to the end (exit $rc)"
grep -q '^p: expectations: 3 passed, 0 failed$' run; ok $? "the expectations over the whole run pass"
diag <run
h5diff cut.h5 long.h5 >diff 2>&1; ok $? "every dataset equals the uninterrupted run's (h5diff)"
diag <diff
/usr/bin/python3 -c "
import h5py; f = h5py.File('cut.h5', 'r'); print(f.attrs['status'])" >status
grep -qx complete status; ok $? "the continued file's status is complete"

# 3. refused
./p --restart long.h5 --duration 3s >run 2>&1; rc=$?
ok $((rc != 2)) "a file that already reaches the duration (exit $rc)"
grep -q 'already reaches t = 3 s; give a longer --duration' run; ok $? "says so"
./p --restart part.h5 --out other.h5 --duration 0.3s >run 2>&1; rc=$?
ok $((rc != 2)) "--out naming another file (exit $rc)"
./p --duration 0.1s --out set.h5 --quiet 2>err
./p --restart set.h5 --set release=20deg --duration 0.2s >run 2>&1; rc=$?
ok $((rc != 4)) "another param is refused (exit $rc)"
grep -q 'was run with the params release=0.17453292519943295, this run has release=0.3490658503988659' run
ok $? "naming both values"
diag <run
./p --restart set.h5 --dt 1us --duration 0.2s >run 2>&1; rc=$?
ok $((rc != 4)) "another dt is refused (exit $rc)"
diag <run
cat >other.sinew <<'EOF'
material steel { E = 200 GPa; density = 7.8 g/cm^3; }
rod beam { material = steel; start = (0, 0, 0) m; direction = (1, 0, 0); length = 1 m;
           radius = 5 mm; elements = 4; }
clamp beam.start;
simulate { duration = 1 ms; }
EOF
"$SC" other.sinew -o other 2>err
./other --restart set.h5 --duration 0.2s >run 2>&1; rc=$?
ok $((rc != 4)) "a file of another model is refused (exit $rc)"
grep -q 'set.h5 was written by another model' run; ok $? "saying so"
diag <run

# 4. implicit rods: the kept factorisations are part of the checkpoint
cd "$ROOT" || exit 1
"$SC" --let implicit=true examples/snake_hardening.sinew -o "$TMP/snake" 2>"$TMP/err"
ok $? "the hardened snake with an implicit body compiles"
cd "$TMP" || exit 1
./snake --integrator imex --dt 125us --duration 0.3s --out snake_full.h5 >run 2>&1
ok $? "an uninterrupted run of 0.3 s at 125 us"
grep 'kicks kept' run | diag
grep -q 'implicit rods: [1-9][0-9]* of 2400 kicks kept an earlier factorisation' run
ok $? "some of its kicks keep an earlier factorisation"
./snake --integrator imex --dt 125us --duration 0.13s --out snake_part.h5 --quiet 2>err
./snake --restart snake_part.h5 --integrator verlet --duration 0.3s >run 2>&1; rc=$?
ok $((rc != 4)) "continuing it with another integrator is refused (exit $rc)"
grep -q 'snake_part.h5 was run with --integrator imex, this run asks for verlet' run
ok $? "naming both"
diag <run
./snake --restart snake_part.h5 --duration 0.3s --quiet >run 2>&1; rc=$?
ok $rc "a run of 0.13 s continued to 0.3 s, its integrator taken from the file (exit $rc)"
h5diff snake_part.h5 snake_full.h5 >diff 2>&1; ok $? "every dataset equals the uninterrupted run's (h5diff)"
diag <diff

# 5. holds let go mid-way (examples/constructs/holds.sinew: the rope's clamp
# at 10 ms, the shaken start's velocity at 5 ms): whether a hold has let go
# is part of the checkpoint, continued before and after the release
cd "$ROOT" || exit 1
"$SC" examples/constructs/holds.sinew -o "$TMP/holds" 2>"$TMP/err"; ok $? "the holds construct compiles"
diag <"$TMP/err"
cd "$TMP" || exit 1
./holds --out holds_full.h5 --quiet 2>err; ok $? "an uninterrupted run of 20 ms, the holds let go at 5 and 10 ms"
for cut in 7ms 12ms; do
  ./holds --duration $cut --out holds_$cut.h5 --quiet 2>err
  ./holds --restart holds_$cut.h5 --quiet >run 2>&1; rc=$?
  ok $rc "a run of $cut continued to 20 ms, its expectations passing (exit $rc)"
  diag <run
  h5diff holds_$cut.h5 holds_full.h5 >diff 2>&1; ok $? "every dataset equals the uninterrupted run's (h5diff, cut at $cut)"
  diag <diff
done

# continued NAME SCENE FULL PART WHAT COMPILED PARTWHAT: SCENE compiled,
# run FULL ms in one go and PART ms, the part continued to FULL: the same
# datasets to the bit
continued() {
  cd "$ROOT" || exit 1
  "$SC" "$2" -o "$TMP/$1" 2>"$TMP/err"; ok $? "$6"
  diag <"$TMP/err"
  cd "$TMP" || exit 1
  ./$1 --duration ${3}ms --out $1_full.h5 --quiet 2>err; ok $? "an uninterrupted run of $3 ms"
  ./$1 --duration ${4}ms --out $1_part.h5 --quiet 2>err; ok $? "a run of $4 ms, $5"
  ./$1 --restart $1_part.h5 --duration ${3}ms --quiet >run 2>&1; rc=$?
  ok $rc "continued to $3 ms (exit $rc)"
  h5diff $1_part.h5 $1_full.h5 >diff 2>&1; ok $? "every dataset equals the uninterrupted run's (h5diff)"
  diag <diff
}

# 6. friction's anchors (obstacle.c) are state: a rope held on a post by
#    stick-slip friction, continued part way through its settling
continued fric examples/constructs/friction.sinew 30 14 "its anchors half stuck, half slipping" \
  "the rope on a post with friction compiles"

# 7. rod-rod friction's anchors (contact.c) are state too: one stick held
#    on two bars, one sliding over them, continued part way
continued rodfric examples/constructs/rod_friction.sinew 40 18 "one pair stuck, one slipping" \
  "the sticks on two bars with rod-rod friction compile"

done_testing
