#!/bin/sh
# test_plot.sh — scripts/sinew-plot: every mode draws a PNG from real and
# synthetic output, and bad input gives one clear line and the right exit
# code (2 usage, 4 input/output), never a Python traceback.
#
#   real output      examples/pendulum.sinew compiled and run for 20 ms
#                    (a hinge, /joints/pivot/angle), and the same run
#                    stopped by SIGINT (status "interrupted at ...")
#   synthetic output h5py writes what docs/runtime.md promises for muscles
#                    (/muscles/NAME/force, stretch, activation, attribute
#                    F_max), which the runtime does not write yet, plus a
#                    file whose angle is a frame behind its /time
#
# python3-h5py and python3-matplotlib are installed by `make test`
# (scripts/deps.sh); their absence is a failure, not a skip.
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
PLOT=$ROOT/scripts/sinew-plot
PY=/usr/bin/python3
TMP=$(mktemp -d "${TMPDIR:-/tmp}/sinew-plot.XXXXXX") || exit 1
trap 'rm -rf "$TMP"' EXIT INT TERM

is_png() { [ "$(head -c 8 "$1" 2>/dev/null | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ]; }

# plot DESCRIPTION ARGS...: exits 0 and writes a PNG to $TMP/out.png
plot() {
  what=$1; shift
  rm -f "$TMP/out.png"
  "$PLOT" "$@" -o "$TMP/out.png" >"$TMP/log" 2>&1
  rc=$?
  [ $rc -eq 0 ] && is_png "$TMP/out.png"; ok $? "$what"
  [ $rc -eq 0 ] || diag <"$TMP/log"
}

# fails CODE MESSAGE DESCRIPTION ARGS...: exits CODE, the last line of stderr
# is MESSAGE exactly, and no traceback
fails() {
  code=$1 msg=$2 what=$3; shift 3
  "$PLOT" "$@" >"$TMP/log" 2>&1
  rc=$?
  last=$(tail -n 1 "$TMP/log")
  [ $rc -eq "$code" ] && [ "$last" = "$msg" ] && ! grep -q Traceback "$TMP/log"
  res=$?
  ok $res "$what: exit $code, \"$msg\""
  [ $res -eq 0 ] || { echo "exit $rc"; cat "$TMP/log"; } | diag
}

$PY -c 'import h5py, matplotlib' 2>"$TMP/log"
ok $? "$PY has h5py and matplotlib (python3-h5py, python3-matplotlib)"
diag <"$TMP/log"

# ---- real output of the runtime
"$SINEWC" examples/pendulum.sinew -o "$TMP/pend" >"$TMP/log" 2>&1 &&
  "$TMP/pend" --quiet --duration 20ms --every 1ms --out "$TMP/pend.h5" >>"$TMP/log" 2>&1
ok $? "pendulum.sinew compiles and runs 20 ms"
diag <"$TMP/log"
"$TMP/pend" --quiet --duration 100s --every 1ms --out "$TMP/stopped.h5" >/dev/null 2>&1 &
pid=$!
sleep 1
kill -INT $pid
wait $pid
ok "$([ $? -eq 130 ]; echo $?)" "the pendulum stopped by SIGINT exits 130"

# ---- synthetic output with muscles (the schema of docs/runtime.md)
$PY - "$TMP" <<'EOF' 2>"$TMP/log"
import sys, h5py, numpy as np
d = sys.argv[1]
t = np.linspace(0, 0.2, 21)
def write(name, fmax=True, behind=False):
    with h5py.File(f"{d}/{name}", "w") as f:
        f.attrs["status"] = "complete"
        f["time"] = t
        f["joints/elbow/angle"] = (np.pi / 2 * (1 - np.exp(-t / 0.05)))[: len(t) - behind]
        f["joints/elbow/force"] = np.zeros((len(t), 3))
        for m, s in (("biceps_short", 1.0), ("biceps_long", 0.8)):
            g = f.create_group(f"muscles/{m}")
            if fmax:
                g.attrs["F_max"] = 700.0 * s
            g["force"] = 500 * s * (1 - np.exp(-t / 0.05))
            g["stretch"] = 1 - 0.15 * (1 - np.exp(-t / 0.05))
            g["activation"] = np.minimum(t / 0.05, 1)
write("arm.h5")
write("arm_nofmax.h5", fmax=False)
write("arm_behind.h5", behind=True)
EOF
ok $? "h5py writes the synthetic files"
diag <"$TMP/log"
printf '# eta, F/F_max\neta,F\n0.7, 0.55\n0.85 0.85\n1.0,1.0\n' >"$TMP/fl.csv"
printf 'u F/F_qs\n0 1\n1 0.41\n3 0.12\n' >"$TMP/fv.txt"
printf '0.7 0.5\n0.8 x\n' >"$TMP/bad.txt"
echo 'not HDF5' >"$TMP/text.h5"

# ---- every mode draws
plot "angle of a real run" angle "$TMP/pend.h5"
plot "angle of a run stopped by SIGINT" angle "$TMP/stopped.h5" --joint pivot
grep -q "note: $TMP/stopped.h5: the run did not complete (status: interrupted at t = " "$TMP/log"
ok $? "the stopped run is plotted with a note"
plot "angle, two real runs overlaid with labels" angle "$TMP/pend.h5" "$TMP/stopped.h5" \
  --label "20 ms" stopped
plot "angle, a file a frame behind overlaid, --label repeated" angle "$TMP/arm.h5" "$TMP/arm_behind.h5" \
  --joint elbow --label original --label hardened
plot "force-length, reference curve only" force-length
plot "force-length with a file's equilibrium points and a CSV of points" force-length \
  "$TMP/arm.h5" --points "$TMP/fl.csv"
plot "force-length of a file without F_max, given --fmax" force-length "$TMP/arm_nofmax.h5" --fmax 700
plot "force-velocity with points" force-velocity --points "$TMP/fv.txt"
plot "muscle" muscle "$TMP/arm.h5"

# ---- bad input: one line, the right exit code
fails 4 "sinew-plot: $TMP/none.h5: no such file" "missing file" angle "$TMP/none.h5" -o "$TMP/x.png"
fails 4 "sinew-plot: $TMP/text.h5: cannot read as HDF5 (Unable to open file (file signature not found))" \
  "not an HDF5 file" angle "$TMP/text.h5" -o "$TMP/x.png"
fails 4 "sinew-plot: $TMP/pend.h5: no dataset /joints/elbow/angle (joints with an angle: pivot)" \
  "missing joint names file and path" angle "$TMP/pend.h5" --joint elbow -o "$TMP/x.png"
fails 4 "sinew-plot: $TMP/pend.h5: no muscles (no dataset /muscles/NAME/force)" \
  "muscle mode on a file without muscles" muscle "$TMP/pend.h5" -o "$TMP/x.png"
fails 4 "sinew-plot: $TMP/bad.txt:2: expected two numbers, got '0.8 x'" \
  "bad points file" force-velocity --points "$TMP/bad.txt" -o "$TMP/x.png"
fails 2 "sinew-plot: $TMP/arm_nofmax.h5: /muscles/biceps_long has no attribute F_max; give --fmax N" \
  "force-length without F_max" force-length "$TMP/arm_nofmax.h5" -o "$TMP/x.png"
fails 2 "sinew-plot: no output file: give -o OUT.png" "no -o" angle "$TMP/pend.h5"
fails 2 "sinew-plot: unknown mode 'angles' (did you mean 'angle'?)" \
  "misspelled mode" angles "$TMP/pend.h5" -o "$TMP/x.png"
fails 2 "sinew-plot: unknown mode 'bars'; modes: angle, force-length, force-velocity, muscle, frames, movie, study" \
  "unknown mode" bars -o "$TMP/x.png"
fails 2 "sinew-plot: unrecognized arguments: --jiont pivot" "unknown option" angle "$TMP/pend.h5" --jiont pivot -o "$TMP/x.png"
fails 2 "sinew-plot: angle takes one or more files" "angle without a file" angle -o "$TMP/x.png"
fails 2 "sinew-plot: 2 labels for 1 file: give one --label per file" "label count" angle "$TMP/pend.h5" --label a b -o "$TMP/x.png"
fails 4 "sinew-plot: /nonexistent/x.png: cannot write ([Errno 2] No such file or directory: '/nonexistent/x.png')" \
  "unwritable output" angle "$TMP/pend.h5" -o /nonexistent/x.png
done_testing
