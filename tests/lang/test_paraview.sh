#!/bin/sh
# test_paraview.sh — the XDMF description a simulator writes beside its HDF5
# file (RUN.h5 -> RUN.xdmf) opens in ParaView as the rods over time:
#
#   1. the cantilever (positions and velocity written, 0.6 s) under a file
#      name with XML's special characters (& < > ' "), opened by Debian's
#      ParaView (pvpython, headless under xvfb-run): time steps = /time, the
#      last step's points = the last frame of /rods/beam/position to 1e-12 m,
#      Tube by the radius point data, the rendered frame's pixels where the
#      tube projects (tests/lang/paraview_rods.py);
#   2. a run stopped by SIGINT lists exactly the frames its file has; one
#      killed outright (SIGKILL) lists the first frames of its file, never one
#      the file lacks; one cut by --restart and continued lists exactly the
#      continued file's frames.
# Rod names cannot carry XML's special characters (an identifier is
# [A-Za-z_][A-Za-z0-9_]*, joined by '.'); their escaping is tested through
# the runtime's API in tests/runtime/test_output.c.
#
# ParaView is heavy (about 500 MB installed), so it is not among make test's
# dependencies: this test installs python3-paraview (and xvfb, for the X
# server Debian's GLX-only build renders into) with scripts/deps.sh when
# missing, and fails, never skips, when they cannot be installed.
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
SC=$SINEWC_CHECK
scratch paraview

sh scripts/deps.sh python3-paraview:/usr/bin/pvpython xvfb:/usr/bin/xvfb-run >"$TMP/deps" 2>&1
rc=$?
ok $rc "python3-paraview and xvfb are installed (scripts/deps.sh)"
diag <"$TMP/deps"
if [ $rc -ne 0 ]; then
  sed 's/^/# deps: /' "$TMP/deps" >&2   # apt's reason, shown by prove
  echo "Bail out! cannot install python3-paraview and xvfb with apt-get"
  exit 1
fi

# frames XDMF H5: the frames the description lists against the file's; ok
# (exit 0) when the description is well-formed XML, lists frames 0..N-1 at
# the times /time has for them, and N is the file's count (or, with
# `prefix`, N >= 1 and no more than the file's).
frames() {
  /usr/bin/python3 - "$1" "$2" "$3" <<'EOF'
import sys, xml.etree.ElementTree as ET, h5py, numpy as np
xdmf, h5, mode = sys.argv[1], sys.argv[2], sys.argv[3]
steps = ET.parse(xdmf).getroot().find("Domain").find("Grid").findall("Grid")
times = np.array([float(g.find("Time").get("Value")) for g in steps])
starts = [int(g.find("Grid/Geometry/DataItem/DataItem").text.split()[0]) for g in steps]
with h5py.File(h5, "r") as f:
    time = f["time"][:]
n, m = len(steps), len(time)
print("the description lists %d frames, the file has %d" % (n, m))
good = starts == list(range(n)) and n <= m and np.array_equal(times, time[:n])
good = good and (n == m if mode == "exact" else n >= 1)
sys.exit(0 if good else 1)
EOF
}

# 1. ParaView opens it
sed 's/^output .*/output "x.h5" every 10 ms { positions beam; velocity beam; }/' \
  examples/cantilever.sinew >"$TMP/cantilever.sinew"
"$SC" "$TMP/cantilever.sinew" -o "$TMP/cantilever" 2>"$TMP/err"
ok $? "the cantilever compiles"
diag <"$TMP/err"
cd "$TMP" || exit 1
run="can&tilever <'1'>\""
./cantilever --duration 0.6s --out "$run.h5" --quiet 2>err
ok $? "it runs 0.6 s into '$run.h5'"
diag <err
[ -f "$run.xdmf" ] && ! [ -e "$run.xdmf.tmp" ]
ok $? "'$run.xdmf' is written beside it (and no temporary file is left)"
grep -q "can&amp;tilever &lt;&apos;1&apos;&gt;&quot;\.h5:/rods/beam/position" "$run.xdmf"
ok $? "the description names the HDF5 file by its base name, escaped"
frames "$run.xdmf" "$run.h5" exact >log 2>&1; ok $? "$(cat log)"
start=$(date +%s)
xvfb-run -a pvpython "$ROOT/tests/lang/paraview_rods.py" "$TMP/$run.xdmf" "$run.h5" \
  "$TMP/rods.png" >pv 2>pverr
rc=$?
# VTK aborts when it cannot open its window on the virtual X server, which
# happens now and then while the machine is loaded (in full `make test` runs
# beside a study on both cores: two failed attempts in a row, then a pass
# alone, with the same files; the abort comes when the picture is rendered,
# after the file's own checks have passed): that is the X server, not the
# file, so it is said and tried again, up to five times in all (three were
# not enough once, in a clean clone's full run at load 5-6, 2026-11-30).  The same
# holds when only the picture's checks fail (the pixels drawn) while every
# check of the file passed: seen once in a full run on a loaded machine
# (checks 15-16), passing alone and under two busy cores since
tries=1
picture_only() {
  grep -q '^not ok' pv && ! grep '^not ok' pv | grep -qv 'pixel'
}
while [ $rc -ne 0 ] && [ $tries -lt 5 ] && { grep -q 'CreateAWindow' pverr || picture_only; }; do
  diag <<EOM
pvpython could not open its window on the virtual X server, or drew a picture other than the tube (exit $rc, attempt $tries); trying again
EOM
  grep '^not ok' pv | diag
  sleep $((2 * tries))
  tries=$((tries + 1))
  xvfb-run -a pvpython "$ROOT/tests/lang/paraview_rods.py" "$TMP/$run.xdmf" "$run.h5" \
    "$TMP/rods.png" >pv 2>pverr
  rc=$?
done
checks=0
while IFS= read -r line; do
  case $line in
  "ok "*) ok 0 "ParaView: ${line#ok * - }"; checks=$((checks + 1)) ;;
  "not ok "*) ok 1 "ParaView: ${line#not ok * - }"; checks=$((checks + 1)) ;;
  esac
done <pv
ok $rc "pvpython exits 0 after $checks checks, in $(($(date +%s) - start)) s"
# on a failure, pvpython's own words go to stderr too, so a CI log shows them
[ $rc -eq 0 ] || { grep -v 'no caching possible' pverr | diag; grep -v 'no caching possible' pverr | tail -20 >&2; }
[ "$checks" -ge 10 ]; ok $? "all 10 checks of paraview_rods.py ran (one rod, velocity written)"
[ -n "$SINEW_PARAVIEW_PNG" ] && cp rods.png "$SINEW_PARAVIEW_PNG"

# 2. stopped early, continued
cd "$ROOT" || exit 1
"$SC" examples/pendulum.sinew -o "$TMP/p" 2>"$TMP/err"; ok $? "the pendulum compiles"
diag <"$TMP/err"
cd "$TMP" || exit 1
./p --duration 30s --out cut.h5 --quiet 2>err &
pid=$!
sleep 1.5
kill -INT $pid
wait $pid; rc=$?
ok $((rc != 130)) "a run stopped by SIGINT (exit $rc)"
frames cut.xdmf cut.h5 exact >log 2>&1; ok $? "after SIGINT $(cat log)"

./p --duration 30s --out killed.h5 --quiet 2>err &
pid=$!
sleep 2.5
kill -KILL $pid
wait $pid; rc=$?
ok $((rc != 137)) "a run killed by SIGKILL (exit $rc)"
frames killed.xdmf killed.h5 prefix >log 2>&1
ok $? "after SIGKILL $(cat log), the first of them (it is rewritten every second)"

reached=$(/usr/bin/python3 -c "
import h5py; print('%.6f' % (h5py.File('cut.h5', 'r')['time'][-1] + 0.05))")
./p --restart cut.h5 --duration "${reached}s" --quiet 2>err; rc=$?
ok $rc "the stopped run continued to t = $reached s (exit $rc)"
diag <err
frames cut.xdmf cut.h5 exact >log 2>&1; ok $? "after --restart $(cat log)"
done_testing
