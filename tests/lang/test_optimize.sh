#!/bin/sh
# test_optimize.sh — SIM --sweep, --optimize and --resume on a model whose
# optimum is known in closed form, on one machine and under mpirun:
#   a soft rod dropped in a vacuum from height h at x0 falls as z = h - g t^2/2
#   (position Verlet is exact for constant acceleration), so the design that
#   puts its centre at z = 1 m, x = 0.3 m at t = 0.1 s is h = 1.04905 m,
#   x0 = 0.3 m;
#   - a grid sweep stores every combination with the closed-form objective;
#     a Latin hypercube uses each stratum of each param once;
#   - CMA-ES finds the design to 1e-6 m, and the recheck of its 3 best
#     designs at dt/2 finds them insensitive to the step (the fall is exact
#     in Verlet: the objectives agree to rounding);
#   - a study stopped with Ctrl-C and resumed gives the file of one that never
#     stopped (tests/lang/study_same.py: every dataset and attribute, bit for
#     bit, but wall_time and rank), and one that spent its budget and runs on
#     with a larger one gives the file of one run with that budget;
#   - `mpirun -np 1`, `-np 2` and `-np 4 --oversubscribe` give the same file,
#     also when rank 1 hangs and its evaluation is re-queued;
#   - a simulator built with --no-mpi sweeps alone and refuses mpirun;
#   - bad use is refused with one line and the exit code of the contract.
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
case $SINEWC in /*) ;; *) SINEWC=$ROOT/$SINEWC ;; esac   # models are also compiled in $TMP
scratch optimize
PY=/usr/bin/python3
SAME="$PY $ROOT/tests/lang/study_same.py"
# same A B / pycheck <<EOF: the comparison's (or the check's) words as TAP
# comments and its exit status as theirs (a pipe into diag would give
# diag's, and the check would assert nothing)
same() { $SAME "$1" "$2" >same.out 2>&1; r=$?; diag <same.out; return $r; }
pycheck() { $PY - >py.out 2>&1; r=$?; diag <py.out; return $r; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export PATH="$ROOT/scripts:$PATH"

cat > "$TMP/drop.sinew" <<'EOF'
# a rod dropped in a vacuum: which start puts its centre at (0.3, 1) m at 0.1 s?
param height = 1.2 m in (0.5 m, 1.5 m);
param x0 = 10 cm in (0 cm, 50 cm);
material soft { E = 1 MPa; density = 1000 kg/m^3; }
rod r { material = soft; start = (x0 - 5 cm, 0 m, height); direction = (1, 0, 0); length = 10 cm;
        radius = 1 cm; elements = 2; }
gravity (0, 0, -9.81) m/s^2;
simulate { dt = 0.2 ms; duration = 0.1 s; }
output "drop.h5" every 10 ms { probe c = centre_of_mass(r); }
maximize -abs(at(z(c), 0.1 s) - 1 m) - abs(at(x(c), 0.1 s) - 0.3 m);
EOF
"$SINEWC" "$TMP/drop.sinew" -o "$TMP/drop" 2>"$TMP/err"
ok $? "the model compiles (with MPI where sinew was built with it)"
diag < "$TMP/err"
"$SINEWC" "$TMP/drop.sinew" --no-mpi -o "$TMP/drop_nompi" 2>"$TMP/err"
ok $? "and with --no-mpi"
cd "$TMP" || exit 1

# ---- grid and Latin hypercube ----
./drop --sweep grid:3 --study grid.h5 --quiet 2>err
ok $? "--sweep grid:3 runs"
pycheck <<'EOF'
import h5py, numpy as np, sys
f = h5py.File("grid.h5", "r")
P, s = f["evaluations/params"][()], f["evaluations/score"][()]
names = [n.decode() if isinstance(n, bytes) else n for n in f["evaluations/params"].attrs["names"]]
h, x0 = P[:, names.index("height")], P[:, names.index("x0")] / 100    # x0 is shown in cm
want = -np.abs(h - 0.5 * 9.81 * 0.01 - 1) - np.abs(x0 - 0.3)
err = np.max(np.abs(s - want))
print(f"grid: {len(s)} designs, h in {sorted(set(np.round(h, 12)))} m; largest error of the "
      f"score against the closed form {err:.2e} m")
sys.exit(0 if len(s) == 9 and err < 1e-12 and f.attrs["status"] == "complete" else 1)
EOF
ok $? "the grid holds its 9 designs, each scored as the closed form says (to 1e-12 m)"
./drop_nompi --sweep lhs:12 --seed 3 --study lhs.h5 --quiet 2>err
ok $? "--sweep lhs:12 by the simulator without MPI"
pycheck <<'EOF'
import h5py, numpy as np, sys
P = h5py.File("lhs.h5", "r")["evaluations/params"][()]
lo, hi = np.array([0.5, 0.0]), np.array([1.5, 50.0])
k = np.floor((P - lo) / (hi - lo) * 12).astype(int)
ok = all(sorted(k[:, j]) == list(range(12)) for j in range(2))
print(f"lhs: strata of h {sorted(k[:, 0])}, of x0 {sorted(k[:, 1])}")
sys.exit(0 if ok else 1)
EOF
ok $? "the Latin hypercube uses each of the 12 strata of both params once"

# ---- CMA-ES ----
./drop --optimize --budget 400 --seed 5 --study opt.h5 2>opt.log
ok $? "--optimize runs"
tail -1 opt.log | diag
pycheck <<'EOF'
import h5py, sys
f = h5py.File("opt.h5", "r")
b = f["best/params"][()]
names = [n.decode() if isinstance(n, bytes) else n for n in f["evaluations/params"].attrs["names"]]
h, x0 = b[names.index("height")], b[names.index("x0")] / 100
eh, ex = abs(h - (1 + 0.5 * 9.81 * 0.01)), abs(x0 - 0.3)
print(f"best h = {h:.9f} m (closed form 1.04905 m, error {eh:.2e}), x0 = {x0:.9f} m "
      f"(0.3 m, error {ex:.2e}), after {len(f['evaluations/score'])} evaluations")
sys.exit(0 if eh < 1e-6 and ex < 1e-6 else 1)
EOF
ok $? "CMA-ES finds h and x0 of the closed form to 1e-6 m"
grep "recheck at dt/2\|best design\|agree at dt and dt/2" opt.log | diag
pycheck <<'EOF'
import h5py, sys
f = h5py.File("opt.h5", "r")
rc, score = f["recheck"], f["evaluations/score"][()]
top = sorted(range(len(score)), key=lambda i: (-score[i], i))[:3]
diff = abs(rc["objective_half"][()] - rc["objective"][()])
print(f"recheck at dt/2 of designs {list(rc['index'][()])} (the 3 best: {top}): objectives "
      f"{list(rc['objective'][()])} m at dt = {rc['dt'][0]} s, differences {list(diff)} m "
      f"(the fall is exact in Verlet: rounding only); floor {rc.attrs['floor']:.3g} m")
sys.exit(0 if list(rc["index"][()]) == top and (rc["sensitive"][()] == 0).all()
         and (diff < 1e-12).all() and (rc["dt"][()] == 2e-4).all() else 1)
EOF
ok $? "the 3 best designs rechecked at dt/2 agree to rounding (the fall is exact in Verlet): insensitive"
[ -s opt.png ] && [ "$(head -c 4 opt.png | od -An -tx1 | tr -d ' \n')" = 89504e47 ]
ok $? "the summary plot opt.png is written (sinew-plot study)"

# ---- --start: CMA-ES from another study's best design ----
# A study started at opt.h5's best with a small step samples its first
# generation around that design (SI values recorded as the start), in
# whichever unit this model shows a param (x0 here in mm, there in cm).
sed 's/param x0 = 10 cm in (0 cm, 50 cm);/param x0 = 100 mm in (0 mm, 500 mm);/' drop.sinew > drop_mm.sinew
"$SINEWC" drop_mm.sinew -o drop_mm 2>err
ok $? "the model with x0 in mm compiles"
./drop_mm --optimize --start opt.h5 --sigma 0.01 --budget 24 --seed 7 --study warm.h5 2>warm.log
ok $? "--optimize --start opt.h5 runs"
grep "starting at the best design of opt.h5" warm.log | diag
pycheck <<'EOF'
import h5py, numpy as np, sys
a, b = h5py.File("opt.h5", "r"), h5py.File("warm.h5", "r")
names = [n.decode() if isinstance(n, bytes) else n for n in a["evaluations/params"].attrs["names"]]
best = a["best/params"][()]
h, x0 = best[names.index("height")], best[names.index("x0")] / 100          # cm -> m
start = dict(kv.split("=") for kv in b.attrs["start"].split(";"))
P, gen = b["evaluations/params"][()], b["evaluations/generation"][()]
first = P[gen == 0]
dh, dx = np.abs(first[:, 0] - h).max(), np.abs(first[:, 1] / 1000 - x0).max()   # mm -> m
print(f"start recorded: height = {start['height']} m, x0 = {start['x0']} m (opt.h5's best: "
      f"{h:.17g} m, {x0:.17g} m); generation 0 within {dh:.2e} m and {dx:.2e} m of it "
      f"(sigma 0.01 of the ranges: 0.01 m and 0.005 m)")
sys.exit(0 if float(start["height"]) == h and abs(float(start["x0"]) - x0) <= 1e-15 * x0
         and dh < 0.05 and dx < 0.025 else 1)
EOF
ok $? "the start is opt.h5's best design in SI, and the first generation is sampled around it"
./drop_mm --optimize --start opt.h5 --sigma 0.01 --budget 48 --seed 7 --study warm48.h5 --quiet 2>/dev/null
./drop_mm --resume warm.h5 --budget 48 --quiet 2>err
ok $? "a study started with --start runs on to a larger budget from its file alone"
same warm48.h5 warm.h5
ok $? "and equals the study run with that budget from the start"
sed -e 's/param x0 = 10 cm in (0 cm, 50 cm);/param x0 = 0.1 in (0, 0.5);/' \
    -e 's/(x0 - 5 cm,/(x0 * 1 m - 5 cm,/' drop.sinew > drop_nounit.sinew
"$SINEWC" drop_nounit.sinew -o drop_nounit 2>err
./drop_nounit --optimize --start opt.h5 --study nounit.h5 >out 2>err; rc=$?
[ $rc -eq 4 ] && grep -q "holds x0 in 'cm', which is not a unit of this model's x0 (dimensionless)" err
ok $? "--start refuses a param whose unit there is of another dimension, and names it (exit $rc)"
diag < err
sed 's/param height = 1.2 m in (0.5 m, 1.5 m);/param height = 1.2 m in (1.1 m, 1.5 m);/' drop.sinew > drop_high.sinew
"$SINEWC" drop_high.sinew -o drop_high 2>err
./drop_high --optimize --start opt.h5 --study high.h5 >out 2>err; rc=$?
[ $rc -eq 2 ] && grep -q "outside this model's range" err
ok $? "--start refuses a best design outside this model's range (exit $rc)"
diag < err
./drop --sweep grid:2 --start opt.h5 --study s.h5 >out 2>err; rc=$?
[ $rc -eq 2 ] && grep -q "belong to --optimize" err
ok $? "--start with --sweep is refused (exit $rc)"
./drop --resume warm.h5 --start opt.h5 >out 2>err; rc=$?
[ $rc -eq 2 ] && grep -q "leave out --start" err
ok $? "--start with --resume is refused (exit $rc)"
./drop --optimize --start grid.h5 --study fromgrid.h5 --budget 12 --quiet 2>err
ok $? "--start takes a sweep's best design too"
./drop --optimize --start opt.h5 --start x0=20cm --study mixed.h5 --budget 6 --quiet 2>err
ok $? "--start FILE with --start NAME=VALUE runs"
pycheck <<'EOF'
import h5py, sys
a, b = h5py.File("opt.h5", "r"), h5py.File("mixed.h5", "r")
names = [n.decode() if isinstance(n, bytes) else n for n in a["evaluations/params"].attrs["names"]]
start = dict(kv.split("=") for kv in b.attrs["start"].split(";"))
h = a["best/params"][()][names.index("height")]
print(f"start: height = {start['height']} m (opt.h5's best {h:.17g} m), x0 = {start['x0']} m "
      f"(--start x0=20cm); varied: {b.attrs['varied']}")
sys.exit(0 if float(start["height"]) == h and float(start["x0"]) == 0.2
         and b.attrs["varied"] == "height;x0" else 1)
EOF
ok $? "NAME=VALUE starts that param there (over the file's value), and it still varies"
fails_start() {   # fails_start PATTERN DESCRIPTION ARGS...
  pattern=$1 what=$2; shift 2
  ./drop --optimize --study bad_start.h5 "$@" >out 2>err; rc=$?
  [ $rc -eq 2 ] && grep -q -- "$pattern" err && [ ! -e bad_start.h5 ]
  ok $? "$what (exit $rc, no study file)"
  diag < err
}
fails_start "outside its range" "--start NAME=VALUE outside the range" --start x0=70cm
fails_start "expected length" "--start NAME=VALUE without its unit" --start x0=7
fails_start "does not vary it" "--start and --set of one param" --set x0=7cm --start x0=7cm
fails_start "starts from one file" "two --start files" --start opt.h5 --start grid.h5

# ---- interrupted and resumed ----
# at dt = 5 us an evaluation takes milliseconds (20,000 steps): Ctrl-C comes
# mid-study
./drop --optimize --budget 300 --seed 5 --dt 5us --study whole.h5 --quiet 2>/dev/null
ok $? "an optimisation at dt = 5 us runs"
./drop --optimize --budget 300 --seed 5 --dt 5us --study cut.h5 --quiet 2>cut.log &
pid=$!
i=0
while [ $i -lt 400 ]; do
  n=$($PY -c "import h5py; f=h5py.File('cut.h5','r',locking=False); print((f['evaluations/status'][()]!=0).sum())" 2>/dev/null)
  [ "${n:-0}" -ge 20 ] && break
  sleep 0.02; i=$((i + 1))
done
kill -INT $pid; wait $pid; rc=$?
done_before=$($PY -c "import h5py; print((h5py.File('cut.h5','r')['evaluations/status'][()]!=0).sum())")
[ $rc -eq 130 ] && [ "$done_before" -lt 300 ]
ok $? "Ctrl-C stops the study after $done_before of 300 evaluations (exit $rc)"
./drop --resume cut.h5 --quiet 2>>cut.log
ok $? "--resume continues it"
same whole.h5 cut.h5
ok $? "the resumed study's file equals the uninterrupted one's"
./drop --optimize --budget 150 --seed 5 --dt 5us --study part.h5 --quiet 2>/dev/null
./drop --resume part.h5 --budget 300 --quiet 2>>cut.log
ok $? "a study that spent its budget of 150 runs on with --resume --budget 300"
same whole.h5 part.h5
ok $? "and its file equals the one run with 300 from the start (the budget attribute too)"
./drop --optimize --study cut.h5 --quiet 2>err; rc=$?
[ $rc -eq 2 ] && grep -q "exists: continue it with --resume cut.h5" err
ok $? "a study file is not overwritten (exit $rc)"
./drop --resume cut.h5 --dt 2ms --quiet 2>err; rc=$?
[ $rc -eq 2 ] && grep -q "ran with duration=" err
ok $? "a resume with another --dt is refused (exit $rc)"

# ---- MPI ----
if command -v mpirun >/dev/null && ./drop --help >/dev/null; then
  for np in 1 2 4; do
    mpirun -np $np ./drop --optimize --budget 400 --seed 5 --study mpi$np.h5 --quiet 2>mpi.err
    ok $? "mpirun -np $np ./drop --optimize"
    same opt.h5 mpi$np.h5
    ok $? "-np $np gives the same results as one process"
  done
  $PY -c "import h5py,numpy as np; print('ranks used with -np 2:', sorted(set(h5py.File('mpi2.h5')['evaluations/rank'][()])))" | diag
  mpirun -np 2 ./drop --sweep grid:4 --study gmpi.h5 --quiet 2>/dev/null &&
    ./drop --sweep grid:4 --study g1.h5 --quiet && same g1.h5 gmpi.h5
  ok $? "a grid sweep under mpirun -np 2 equals one process's"
  SINEW_STUDY_FAULT=hang:1:3 mpirun -np 2 ./drop --optimize --budget 400 --seed 5 \
    --study hang.h5 --eval-timeout 2s --quiet 2>hang.err
  grep "has not answered" hang.err | diag
  same opt.h5 hang.h5
  ok $? "rank 1 hangs on its 3rd evaluation: re-queued after 2 s, same results"
  mpirun -np 2 ./drop_nompi --sweep grid:2 --study nompi.h5 --quiet 2>err; rc=$?
  grep -q "built without MPI" err
  ok $? "a simulator built with --no-mpi refuses to run under mpirun -np 2 (exit $rc)"
fi

# ---- bad use ----
fails() {   # fails CODE PATTERN DESCRIPTION ARGS...
  code=$1 pattern=$2 what=$3; shift 3
  ./drop "$@" >out 2>err; rc=$?
  [ $rc -eq "$code" ] && grep -q -- "$pattern" err
  ok $? "$what (exit $rc)"
  [ $rc -eq "$code" ] || diag < err
}
fails 2 "belong to --optimize" "--budget with --sweep" --sweep grid:2 --budget 10
fails 2 "expected grid:K" "--sweep with a misspelt kind" --sweep grad:3
fails 2 "belong to --sweep or --optimize" "--seed alone" --seed 3
fails 4 "cannot read" "--resume of a missing file" --resume nothere.h5
fails 2 "nothing to vary" "every ranged param fixed by --set" --optimize --set height=1m \
  --set x0=2cm --study none.h5
fails 2 "leave out --out" "--out with --optimize" --optimize --out x.h5
done_testing
