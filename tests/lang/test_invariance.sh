#!/bin/sh
# test_invariance.sh — nothing outside the model changes a trajectory
# (issue 30): the frog-like hind leg of tests/scenes/frog_leg (a new user's
# model; its outcome moved 2x with --every and with its expect lines before
# the run loop's held steps, docs/runtime.md) is run for 0.1 s
#   - as written (frames every 1 ms, expect lines, an objective),
#   - with --every 0.3 ms (not a whole number of steps: a note says where the
#     frames fall) and --every 7 ms,
#   - with its expect, maximize and penalty lines removed,
#   - with one probe fewer in its output (output selection),
#   - on 2 threads (over 20 ms),
# and the last frame's positions of the foot, the knee's angle and the
# work done (17 digits, h5dump) must be the same bits in every run; --every
# leaves dt as it is (--info).
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
case $SINEWC in /*) ;; *) SINEWC=$ROOT/$SINEWC ;; esac   # models are compiled in $TMP
scratch invariance
cd "$TMP" || exit 1
cp "$ROOT"/tests/scenes/frog_leg/*.sinew .
grep -v '^expect\|^maximize\|^penalty\|^# \.\.\. without\|^# body over\|^# golden\|^# the study' frog.sinew >bare.sinew
grep -v 'probe body' frog.sinew >fewer.sinew
for m in frog bare fewer; do "$SINEWC" $m.sinew -o $m 2>>err || echo "$m failed" >>err; done
! grep -q failed err
ok $? "the frog leg and its two variants compile"
diag <err

# the last frame of a dataset, one value a line, 17 digits (h5dump)
last() {
  n=$(h5ls "$1$2" | sed 's/.*{\([0-9]*\).*/\1/')
  h5dump -A 0 -y -w 0 -m %.17g -d "$2" "$1" | sed -n '/DATA {/,/^ *}/p' | sed '1d;$d' |
    tr ',' '\n' | grep -Eo -- '-?[0-9][0-9.e+-]*' >vals.tmp
  total=$(wc -l <vals.tmp)
  [ "$n" -gt 0 ] && tail -n "$((total / n))" vals.tmp | tr '\n' ' '
}
state() { echo "$(last "$1" /rods/right.foot/position) $(last "$1" /joints/right.knee_joint/angle) $(last "$1" /diagnostics/energy)"; }

./frog --duration 0.1s --quiet --out a.h5 2>a.log; ok $? "as written"
ref=$(state a.h5)
echo "# last frame: $ref" | cut -c1-300
[ "$(echo "$ref" | wc -w)" = 25 ]; ok $? "its last frame is read (7 nodes x 3, an angle, 3 energies)"
check() {   # check NAME FILE: the same last frame
  s=$(state "$2")
  [ "$s" = "$ref" ]; r=$?
  [ $r = 0 ] || { echo "# $1: $s" | cut -c1-300; }
  ok $r "$1: the same bits"
}
./frog --duration 0.1s --every 0.3ms --out b.h5 2>b.log; ok $? "--every 0.3ms"
diag <b.log
grep -q "frog: note: a frame every 300 us (--every) is 58.5 steps of dt = 5.12821 us; frames come every 59 steps, 302.564 us apart" b.log
ok $? "with a note of where its frames fall"
check "--every 0.3 ms" b.h5
./frog --duration 0.1s --every 7ms --quiet --out c.h5 2>/dev/null; check "--every 7 ms" c.h5
./bare --duration 0.1s --quiet --out d.h5 2>/dev/null; check "without its expect, maximize and penalty lines" d.h5
./fewer --duration 0.1s --quiet --out e.h5 2>/dev/null; check "with one probe fewer" e.h5
# on 2 threads, over 20 ms (a step of this small scene is a few barriers;
# on a loaded machine two spinning threads wait long for each other)
./frog --duration 20ms --quiet --out g.h5 2>/dev/null
ref=$(state g.h5)
./frog --duration 20ms --every 0.3ms --threads 2 --quiet --out f.h5 2>/dev/null
check "on 2 threads with --every 0.3 ms (20 ms)" f.h5
dt1=$(./frog --info | grep '^dt:'); dt2=$(./frog --info --every 0.3ms 2>/dev/null | grep '^dt:')
echo "# $dt1"
[ -n "$dt1" ] && [ "$dt1" = "$dt2" ]
ok $? "--every leaves dt alone (--info)"
done_testing
