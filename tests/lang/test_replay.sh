#!/bin/sh
# test_replay.sh — study files keep every design in SI (/evaluations/params_si)
# and SIM --replay STUDY.h5 [best|N] runs one design into a run file, on
# examples/constructs/objective.sinew cut to 10 ms (frames every 1 ms, so
# that frames and the objective's sampling times both end the run loop's
# chunks of steps; a release angle in degrees, an objective in cm):
#   - a CMA-ES study and a grid sweep (at --dt 5 us, where the short bars go
#     unstable) store params_si beside params, with SI units per param;
#   - --replay (the best), --replay N and --replay FILE best give a run file
#     whose objective, penalty and score are the study's for that row, bit
#     for bit (python3/h5py reads both files; the study stores them in cm,
#     the run file in m, and the study's value is the run's divided by the
#     unit's scale, as the study divides), whose params attribute (SI, 17
#     digits) is that row of params_si, and which ends at the row's sim_time;
#   - a study under mpirun -np 2 stores the same params_si and replays alike;
#   - the study's recheck of its best design at dt/2, half the step the
#     simulator chose for it, is a plain run's of that design at that --dt;
#   - a study file of before params_si (the dataset deleted) still replays
#     (the values shown, converted, with a warning), --resume gives it
#     params_si again (the file then equals the original, bit for bit) and
#     --start still reads it;
#   - bad use is refused with the exit code of the contract and a message
#     that names the file: a file that is not a study, a missing one, a study
#     of another model, N out of range, a design that failed, a study without
#     a best, --replay with --sweep, --optimize, --resume, --set of a varied
#     param, --set of a held one that disagrees, --dt; --every is allowed
#     and changes nothing of the objective.
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
case $SINEWC in /*) ;; *) SINEWC=$ROOT/$SINEWC ;; esac   # models are also compiled in $TMP
scratch replay
PY=/usr/bin/python3
SAME="$PY $ROOT/tests/lang/study_same.py"
same() { $SAME "$1" "$2" >same.out 2>&1; r=$?; diag <same.out; return $r; }
pycheck() { $PY - "$@" >py.out 2>&1; r=$?; diag <py.out; return $r; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1

sed -e 's/0\.5 s, 1 s/5 ms, 10 ms/' -e 's/0 s, 1 s/0 s, 10 ms/g' \
    -e 's/duration = 1 s/duration = 10 ms/' -e 's/every 10 ms/every 1 ms/' \
    examples/constructs/objective.sinew > "$TMP/obj.sinew"
grep -q "duration = 10 ms" "$TMP/obj.sinew" && grep -q "mean_over(z(tip), 5 ms, 10 ms)" "$TMP/obj.sinew"
ok $? "objective.sinew cut to 10 ms"
"$SINEWC" "$TMP/obj.sinew" -o "$TMP/obj" 2>"$TMP/err"
ok $? "the model compiles"
diag < "$TMP/err"
cd "$TMP" || exit 1

# replays STUDY ROW RUN: the run file RUN holds row ROW of STUDY's
# objective, penalty and score bit for bit, its params attribute is the row
# of params_si, and it ends at the row's sim_time
replays() {
  pycheck "$@" <<'EOF'
import h5py, sys
study, row, run = sys.argv[1], int(sys.argv[2]), sys.argv[3]
s, r = h5py.File(study, "r"), h5py.File(run, "r")
ev = s["evaluations"]
scale = {"cm": 0.01, "m": 1.0}[s.attrs["objective_units"]]   # the study's unit, in SI
assert r.attrs["objective_units"] == "m"
ok = True
for k in ("objective", "penalty", "score"):
    there, here = float(ev[k][row]), float(r.attrs[k]) / scale
    print(f"{study} row {row} {k}: study {there!r} {s.attrs['objective_units']}, "
          f"replay {here!r} (run file {float(r.attrs[k])!r} m)")
    ok &= there.hex() == here.hex()
names = [n.decode() if isinstance(n, bytes) else n for n in ev["params_si"].attrs["names"]]
si = dict(zip(names, ev["params_si"][row]))
ran = {k: float(v) for k, v in (kv.split("=") for kv in r.attrs["params"].split(";"))}
print(f"params_si row {row}: {si}; run file params: {ran}")
ok &= all(ran[n].hex() == float(si[n]).hex() for n in names) and set(ran) == set(names)
t_study, t_run = float(ev["sim_time"][row]), float(r["time"][-1])
print(f"sim_time {t_study!r} s, run file's last frame at {t_run!r} s")
ok &= t_study.hex() == t_run.hex()
sys.exit(0 if ok else 1)
EOF
}

# ---- a CMA-ES study: params_si ----
./obj --optimize --budget 12 --seed 3 --study opt.h5 --quiet 2>err
ok $? "--optimize --budget 12 runs"
pycheck <<'EOF'
import h5py, math, sys
f = h5py.File("opt.h5", "r")
ev = f["evaluations"]
P, S = ev["params"][()], ev["params_si"][()]
names = [n.decode() if isinstance(n, bytes) else n for n in ev["params_si"].attrs["names"]]
units = [u.decode() if isinstance(u, bytes) else u for u in ev["params_si"].attrs["units"]]
shown = [u.decode() if isinstance(u, bytes) else u for u in ev["params"].attrs["units"]]
scale = [math.pi / 180, 1.0, 1.0]
lost = sum(1 for i in range(len(S)) for j in range(3) if (P[i, j] * scale[j]).hex() != S[i, j].hex())
close = all(abs(P[i, j] * scale[j] - S[i, j]) <= 1e-15 * abs(S[i, j]) for i in range(len(S)) for j in range(3))
print(f"params_si {S.shape} in {units} (shown in {shown}), names {names}; "
      f"{lost} of {S.size} values shown and converted back miss their SI value in the last bits")
sys.exit(0 if S.shape == P.shape == (12, 3) and names == ["release", "reach", "limit"]
         and units == ["rad", "m", "N"] and close and (S[:, 2] == 4.0).all() else 1)
EOF
ok $? "the study stores params_si [12, 3] in rad, m, N beside params in deg, m, N"
best=$($PY -c "import h5py; print(int(h5py.File('opt.h5','r')['best'].attrs['index']))")
# the recheck at dt/2 of its best (the step the simulator chose for that
# design, halved): a plain run of the design with --dt of that value
pycheck <<'EOF'
import h5py, subprocess, sys
f = h5py.File("opt.h5", "r")
ev, rc = f["evaluations"], f["recheck"]
i, dt = int(rc["index"][0]), float(rc["dt"][0])
names = [n.decode() if isinstance(n, bytes) else n for n in ev["params_si"].attrs["names"]]
units = [n.decode() if isinstance(n, bytes) else n for n in ev["params_si"].attrs["units"]]
sets = [a for n, u, v in zip(names, units, ev["params_si"][i]) for a in ("--set", f"{n}={float(v)!r}{u}")]
subprocess.run(["./obj", *sets, "--dt", repr(dt / 2), "--out", "half.h5", "--quiet"], check=True)
here = float(h5py.File("half.h5", "r").attrs["objective"]) / 0.01        # m -> cm
there = float(rc["objective_half"][0])
print(f"design {i} (the best) rechecked at dt/2 = {dt / 2!r} s (the chosen step halved): "
      f"{there!r} cm; a run with --dt {dt / 2!r}: {here!r} cm; at dt: {float(rc['objective'][0])!r} cm")
sys.exit(0 if i == int(f["best"].attrs["index"]) and here.hex() == there.hex() else 1)
EOF
ok $? "the study's recheck of its best at half the step it chose is a plain run's at that --dt, bit for bit"

# ---- --replay: the best, a row, "best" ----
./obj --replay opt.h5 --out best.h5 2>best.log
ok $? "--replay opt.h5 runs its best design (evaluation $best)"
diag < best.log
grep -q "replaying evaluation $best of opt.h5, its best (score " best.log &&
  grep -q "release = .* deg, reach = .* m" best.log &&
  grep -q "the objective is evaluation $best's of opt.h5, bit for bit" best.log
ok $? "it says which design it replays, with its params as shown, and that the objective matches"
replays opt.h5 "$best" best.h5
ok $? "the run file's objective, penalty and score are the study's for row $best, bit for bit; its params are params_si's"
row=5
[ "$row" = "$best" ] && row=6
./obj --replay opt.h5 $row --out row.h5 --quiet 2>row.log
ok $? "--replay opt.h5 $row runs evaluation $row (0-based: row $row of /evaluations)"
replays opt.h5 $row row.h5
ok $? "and reproduces row $row's objective bit for bit"
./obj --replay opt.h5 best --out best2.h5 --quiet 2>err && replays opt.h5 "$best" best2.h5
ok $? "--replay opt.h5 best is the default"
./obj --replay opt.h5 $row --threads 2 --out row2.h5 --quiet 2>err && replays opt.h5 $row row2.h5
ok $? "on 2 threads too (the results are the same bits for any --threads)"
./obj --replay opt.h5 --set limit=4N --out agree.h5 --quiet 2>err && replays opt.h5 "$best" agree.h5
ok $? "--set of a held param that agrees with the study's value is accepted"
# what the issue did by hand: the values shown, given back with --set
shown=$($PY -c "
import h5py; f = h5py.File('opt.h5', 'r'); p = f['evaluations/params'][$best]
print(f'--set release={p[0]!r}deg --set reach={p[1]!r}m')")
./obj $shown --out byhand.h5 --quiet 2>err
$PY -c "
import h5py
a, b = h5py.File('best.h5', 'r'), h5py.File('byhand.h5', 'r')
print(f'by hand ($shown): objective {b.attrs[\"objective\"]!r} m, params {b.attrs[\"params\"]}; '
      f'--replay: {a.attrs[\"objective\"]!r} m, params {a.attrs[\"params\"]}')" | diag

# ---- a grid sweep at --dt 5 us: some designs unstable ----
./obj --sweep grid:3 --dt 5us --study grid.h5 --quiet 2>err
ok $? "--sweep grid:3 --dt 5us runs"
pycheck <<'EOF'
import h5py, sys
f = h5py.File("grid.h5", "r")
st = list(f["evaluations/status"][()])
print(f"statuses {st} (1 ok, 2 unstable); run_settings {f.attrs['run_settings']}; best {f['best'].attrs['index']}")
sys.exit(0 if 1 in st and 2 in st and st[0] == 2 else 1)
EOF
ok $? "the grid has designs that ran and designs that went unstable (evaluation 0)"
gbest=$($PY -c "import h5py; print(int(h5py.File('grid.h5','r')['best'].attrs['index']))")
./obj --replay grid.h5 --out gbest.h5 --quiet 2>err && replays grid.h5 "$gbest" gbest.h5
ok $? "--replay grid.h5 (evaluation $gbest, at the study's dt = 5 us) reproduces its objective bit for bit"
./obj --replay grid.h5 2 --out g2.h5 --quiet 2>err && replays grid.h5 2 g2.h5
ok $? "--replay grid.h5 2 too"
$PY -c "import h5py; print('dt of the replay:', h5py.File('g2.h5','r').attrs['dt'])" | diag

# ---- under mpirun ----
if command -v mpirun >/dev/null && ./obj --help >/dev/null; then
  mpirun -np 2 ./obj --optimize --budget 12 --seed 3 --study mpi2.h5 --quiet 2>mpi.err
  ok $? "mpirun -np 2 ./obj --optimize"
  same opt.h5 mpi2.h5
  ok $? "its file equals one process's, params_si too"
  ./obj --replay mpi2.h5 $row --out mrow.h5 --quiet 2>err && replays mpi2.h5 $row mrow.h5
  ok $? "and its evaluation $row replays bit for bit"
fi

# ---- a study file of before params_si ----
cp opt.h5 old.h5
$PY -c "import h5py; f = h5py.File('old.h5', 'r+'); del f['evaluations/params_si']"
./obj --replay old.h5 --out old_run.h5 2>old.log
rc=$?
[ $rc -eq 0 ] && grep -q "warning: --replay old.h5: the file has no /evaluations/params_si" old.log
ok $? "a study file without params_si still replays, with a warning (exit $rc)"
grep "objective" old.log | diag
# the issue's case: a design whose angle, shown in deg and converted back,
# misses the radians evaluated by an ulp
lossy=$($PY -c "
import h5py, math
ev = h5py.File('opt.h5', 'r')['evaluations']
P, S, k = ev['params'][()], ev['params_si'][()], 1 / (1 / (math.pi / 180))
print(next((i for i in range(len(S)) if (P[i, 0] * k).hex() != S[i, 0].hex()), ''))")
if [ -n "$lossy" ]; then
  ./obj --replay old.h5 "$lossy" --out old_lossy.h5 2>old_lossy.log
  ./obj --replay opt.h5 "$lossy" --out lossy.h5 --quiet 2>err && replays opt.h5 "$lossy" lossy.h5
  ok $? "evaluation $lossy, whose angle shown in deg does not convert back to its radians, replays bit for bit from params_si"
  pycheck "$lossy" <<'EOF'
import h5py, sys
row = int(sys.argv[1])
si = float(h5py.File("opt.h5", "r")["evaluations/params_si"][row, 0])
old = h5py.File("old_lossy.h5", "r").attrs["params"]
ran = float(dict(kv.split("=") for kv in old.split(";"))["release"])
print(f"release evaluated {si!r} rad; from the values shown (no params_si) {ran!r} rad")
sys.exit(0 if ran != si and abs(ran - si) <= 4e-16 * si else 1)
EOF
  ok $? "from the file without params_si it runs the angle converted back, an ulp or so away"
  grep "objective" old_lossy.log | diag
else
  ok 0 "# SKIP no design of opt.h5 loses bits shown in deg"
  ok 0 "# SKIP no design of opt.h5 loses bits shown in deg"
fi
./obj --optimize --start old.h5 --budget 6 --sigma 0.01 --study warm_old.h5 --quiet 2>err
ok $? "--start reads it (the best design as shown, converted)"
./obj --optimize --start opt.h5 --budget 6 --sigma 0.01 --study warm.h5 --quiet 2>err
pycheck <<'EOF'
import h5py, sys
a, b = h5py.File("opt.h5", "r"), h5py.File("warm.h5", "r")
i = int(a["best"].attrs["index"])
si = a["evaluations/params_si"][i]
start = {k: float(v) for k, v in (kv.split("=") for kv in b.attrs["start"].split(";"))}
print(f"--start opt.h5: start {start}; opt.h5's best in SI {list(si)}")
sys.exit(0 if start["release"].hex() == float(si[0]).hex() and start["reach"].hex() == float(si[1]).hex() else 1)
EOF
ok $? "--start of a file with params_si starts at its best's SI values, bit for bit"
./obj --resume old.h5 --quiet 2>err
ok $? "--resume of the file without params_si runs"
same opt.h5 old.h5
ok $? "and gives it params_si: the file equals the original, bit for bit"

# ---- bad use ----
fails() {   # fails CODE PATTERN DESCRIPTION ARGS...
  code=$1 pattern=$2 what=$3; shift 3
  ./obj "$@" --out bad.h5 >out 2>err; rc=$?
  [ $rc -eq "$code" ] && grep -q -- "$pattern" err
  ok $? "$what (exit $rc)"
  diag < err
}
fails 4 "best.h5 is not a sinew study file" "a run file is not a study" --replay best.h5
fails 4 "cannot read 'nothere.h5'" "a missing file" --replay nothere.h5
sed 's/param limit = 4 N;/param limit = 5 N;/' obj.sinew > other.sinew
"$SINEWC" other.sinew -o other 2>err
./other --replay opt.h5 --out bad.h5 >out 2>err; rc=$?
[ $rc -eq 4 ] && grep -q "opt.h5 is a study of another model" err
ok $? "a study of another model (exit $rc)"
diag < err
fails 2 "opt.h5 holds 12 evaluations (0 to 11): there is no evaluation 12" "N out of range" \
  --replay opt.h5 12
fails 2 "grid.h5: evaluation 0 is unstable: it has no objective to reproduce" \
  "a design that failed" --replay grid.h5 0
./obj --sweep grid:2 --dt 8us --study none.h5 --quiet 2>/dev/null
fails 2 "none.h5 has no best design" "a study none of whose designs ran" --replay none.h5
fails 2 "--replay opt.h5 runs one design" "--replay with --sweep" --replay opt.h5 --sweep grid:2
fails 2 "--replay opt.h5 runs one design" "--replay with --optimize" --replay opt.h5 --optimize
fails 2 "--replay opt.h5 runs one design" "--replay with --resume" --replay opt.h5 --resume opt.h5
fails 2 "--replay opt.h5: the study varied release, so the design sets it: leave out --set release" \
  "--replay with --set of a varied param" --replay opt.h5 --set release=10deg
fails 2 "--replay opt.h5: its evaluations ran with limit = 4 (SI); --set must agree" \
  "--replay with --set of a held param that disagrees" --replay opt.h5 --set limit=5N
fails 2 "--replay grid.h5: its evaluations ran with duration=" "--replay with another --dt" \
  --replay grid.h5 --dt 2us
# frames change nothing of the steps (held steps, integrate.c): another
# --every writes other frames of the same run
./obj --replay opt.h5 --every 0.3ms --out every.h5 2>every.log &&
  grep -q "the objective is evaluation $best's of opt.h5, bit for bit" every.log &&
  replays opt.h5 "$best" every.h5
ok $? "--replay with another --every (0.3 ms) reproduces the objective bit for bit"
diag < every.log
fails 2 "expected a whole number" "--replay with an N beyond any study" --replay opt.h5 99999999999
done_testing
