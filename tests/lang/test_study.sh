#!/bin/sh
# test_study.sh — scripts/sinew-study: a tiny speed/accuracy study of a
# 20-element cantilever (0.2 s, 3 time steps, position Verlet and PEFRL)
# gives the rows asked for, a reference whose error is exactly 0, Verlet
# errors that fall as dt^2 (the measured ratios are printed), a table on
# stdout equal to table.md, a CSV and a PNG; a ladder with an unstable step
# and a second compile-time variant records the unstable runs as rows; and
# bad input gives one clear line and the right exit code (2 usage, 4 input
# or output), never a Python traceback.
#
# The scene is written here, undamped: linear damping enters the kick
# explicitly and makes a transient first order in dt (docs/physics.md), so
# examples/cantilever.sinew, which is damped, would show a ratio near 2.
# The reference is PEFRL at the smallest dt: fourth order, its own error is
# below a thousandth of Verlet's there, so Verlet's errors are its own.
#
# python3-h5py and python3-matplotlib are installed by `make test`
# (scripts/deps.sh); their absence is a failure, not a skip.
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
STUDY=$ROOT/scripts/sinew-study
SC=$ROOT/bin/sinewc
PY=/usr/bin/python3
TMP=$(mktemp -d "${TMPDIR:-/tmp}/sinew-study.XXXXXX") || exit 1
trap 'rm -rf "$TMP"' EXIT INT TERM

is_png() { [ -s "$1" ] && [ "$(head -c 8 "$1" 2>/dev/null | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ]; }

# fails CODE MESSAGE DESCRIPTION ARGS...: exits CODE, the last line of stderr
# is MESSAGE (exactly, but for a '*', which stands for a number the runtime
# computes), and no traceback
fails() {
  code=$1 msg=$2 what=$3; shift 3
  "$STUDY" "$@" >"$TMP/log" 2>&1
  rc=$?
  last=$(tail -n 1 "$TMP/log")
  pattern=$(printf '%s' "$msg" | sed 's/[][?]/\\&/g')
  # shellcheck disable=SC2254
  case $last in $pattern) same=0 ;; *) same=1 ;; esac
  [ $rc -eq "$code" ] && [ $same -eq 0 ] && ! grep -q Traceback "$TMP/log"
  res=$?
  ok $res "$what: exit $code, \"$msg\""
  [ $res -eq 0 ] || { echo "exit $rc"; cat "$TMP/log"; } | diag
}

# csv FILE VARIANT INTEGRATOR DT_S COLUMN: one field of a row of table.csv
csv() {
  $PY - "$@" <<'EOF'
import csv, sys
path, variant, integ, dt, col = sys.argv[1:]
for row in csv.DictReader(open(path)):
    if row["variant"] == variant and row["integrator"] == integ and float(row["dt_s"]) == float(dt):
        print(row[col])
EOF
}

$PY -c 'import h5py, matplotlib' 2>"$TMP/log"
ok $? "$PY has h5py and matplotlib (python3-h5py, python3-matplotlib)"
diag <"$TMP/log"

cat >"$TMP/beam.sinew" <<'EOF'
# An undamped cantilever under a ramped tip load.
param load = 0.5 N;
material soft { E = 1 MPa; density = 1000 kg/m^3; poisson = 0.5; }
rod beam {
  material = soft;
  start = (0, 0, 0) m;
  direction = (1, 0, 0);
  normal = (0, 0, 1);
  length = 1 m;
  radius = 25 mm;
  elements = 20;
}
clamp beam.start;
force beam.end = (0, 0, -1) * ramp(0 N, load, over = 0.5 s);
simulate { dt = 50 us; duration = 0.2 s; }
output "beam.h5" every 10 ms;
EOF
BEAM=$TMP/beam.sinew
TIP='tip=/rods/beam/position[-1]'

# ---- the study: 3 dts x 2 integrators
"$STUDY" "$BEAM" --out "$TMP/s" --sinewc "$SC" --observable "$TIP" \
  --observable tipz=/rods/beam/position[-1,2] --dt 200us,100us,50us \
  --integrator verlet,pefrl --reference integrator=pefrl,dt=50us >"$TMP/stdout" 2>"$TMP/log"
rc=$?
ok $rc "a study of 3 dts x 2 integrators runs"
[ $rc -eq 0 ] || diag <"$TMP/log"
! grep -q Traceback "$TMP/log"; ok $? "no traceback"
rows=$(grep -c '^| base | ' "$TMP/s/table.md")
[ "$rows" -eq 6 ]; ok $? "table.md has 6 rows (got $rows)"
for i in verlet pefrl; do
  n=$(grep -c "^| base | $i | \(50\|100\|200\) us | " "$TMP/s/table.md")
  [ "$n" -eq 3 ]; ok $? "table.md: $i at 50, 100 and 200 us"
done
grep -q '^| variant | integrator | dt | steps | wall (s) | cpu (s) | x faster | tip error (m) | tipz error (m) |$' \
  "$TMP/s/table.md"; ok $? "table.md has the header with one error column per observable"
cmp -s "$TMP/stdout" "$TMP/s/table.md"; ok $? "the table printed is table.md"
grep -q '^| base | pefrl | 50 us | 4000 | [0-9.]* | [0-9.]* | 1 (reference) | 0 m (0 %) | 0 m (0 %) |$' \
  "$TMP/s/table.md"; ok $? "table.md: the reference row, 4000 steps, error 0"
[ "$(csv "$TMP/s/table.csv" base pefrl 5e-5 tip_error_m)" = 0 ] &&
  [ "$(csv "$TMP/s/table.csv" base pefrl 5e-5 tip_error_rel)" = 0 ] &&
  [ "$(csv "$TMP/s/table.csv" base pefrl 5e-5 reference)" = 1 ]
ok $? "table.csv: the reference's error is exactly 0"
[ "$(grep -c . "$TMP/s/table.csv")" -eq 7 ]; ok $? "table.csv: a header and 6 rows"
e50=$(csv "$TMP/s/table.csv" base verlet 5e-5 tip_error_m)
e100=$(csv "$TMP/s/table.csv" base verlet 1e-4 tip_error_m)
e200=$(csv "$TMP/s/table.csv" base verlet 2e-4 tip_error_m)
awk -v a="$e50" -v b="$e100" -v c="$e200" 'BEGIN { exit !(a > 0 && a < b && b < c) }'
ok $? "verlet: the error falls as dt falls ($e200, $e100, $e50 m)"
r1=$(awk -v a="$e100" -v b="$e200" 'BEGIN { printf "%.3f", b / a }')
r2=$(awk -v a="$e50" -v b="$e100" 'BEGIN { printf "%.3f", b / a }')
echo "# verlet error ratios: e(200us)/e(100us) = $r1, e(100us)/e(50us) = $r2 (second order: 4)"
awk -v r="$r1" 'BEGIN { exit !(r > 2.5 && r < 6) }'; ok $? "verlet: e(200us)/e(100us) = $r1, in (2.5, 6)"
awk -v r="$r2" 'BEGIN { exit !(r > 2.5 && r < 6) }'; ok $? "verlet: e(100us)/e(50us) = $r2, in (2.5, 6)"
p100=$(csv "$TMP/s/table.csv" base pefrl 1e-4 tip_error_m)
awk -v p="$p100" -v e="$e100" 'BEGIN { exit !(p < e / 100) }'
ok $? "pefrl at 100 us: error $p100 m, below a hundredth of verlet's"
is_png "$TMP/s/pareto.png"; ok $? "pareto.png is a PNG of $(wc -c <"$TMP/s/pareto.png" 2>/dev/null) bytes"

# ---- unstable runs are rows; compile-time variants.  -Werror changes no
# code, so that variant must give the base's bits when the reference writes
# the same frames (a frame ends a run of fused steps, so a reference with
# ten times the frames, the default, differs from it at round-off); a --let
# variant (sinewc --let, which sets a top-level let) changes the scene.
"$STUDY" "$BEAM" --out "$TMP/u" --sinewc "$SC" --observable "$TIP" --dt 100us,1.5ms \
  --variant base --variant strict:-Werror --plot "$TMP/u.png" --clock cpu --reference-every 10ms \
  --quiet >"$TMP/stdout" 2>"$TMP/log"
ok $? "a study with a step above the stable limit and a second variant exits 0"
diag <"$TMP/log"
[ ! -s "$TMP/stdout" ]; ok $? "--quiet prints nothing"
for v in base strict; do
  st=$(csv "$TMP/u/table.csv" $v verlet 1.5e-3 status)
  case $st in "unstable at t = "*) r=0 ;; *) r=1 ;; esac
  ok $r "$v at 1.5 ms is recorded as '$st'"
  grep -q "^| $v | verlet | 1.5 ms | 133 | [0-9.]* (stopped) | [0-9.]* (stopped) | - | unstable at t = " "$TMP/u/table.md"
  ok $? "$v at 1.5 ms: a table row, its wall time marked stopped"
done
grep -q '^| variant | integrator | dt | steps | wall (s) | cpu (s) | x faster (cpu) | tip error (m) |$' \
  "$TMP/u/table.md"; ok $? "--clock cpu: x faster by processor time, said in the header"
[ "$(csv "$TMP/u/table.csv" base verlet 1e-4 reference)" = 1 ]
ok $? "the default reference is the base variant's smallest dt"
[ "$(csv "$TMP/u/table.csv" strict verlet 1e-4 tip_error_m)" = 0 ]
ok $? "the -Werror variant gives the base's bits: error 0"
is_png "$TMP/u.png"; ok $? "--plot names the PNG"
{ echo 'let n = 20;'; sed 's/elements = 20;/elements = n;/' "$BEAM"; } >"$TMP/let.sinew"
"$STUDY" "$TMP/let.sinew" --out "$TMP/l" --sinewc "$SC" --observable "$TIP" --dt 100us \
  --variant base --variant coarse:'--let n=10' --quiet >/dev/null 2>"$TMP/log"
ok $? "a --let variant compiles and runs"
diag <"$TMP/log"
e=$(csv "$TMP/l/table.csv" coarse verlet 1e-4 tip_error_m)
awk -v e="$e" 'BEGIN { exit !(e > 0) }'
ok $? "the --let variant (10 elements, not 20) differs from the base: $e m"

# ---- bad input: one line, the right exit code
fails 4 "sinew-study: observable 'tip': no dataset /rods/bean/position in the output of $BEAM (did you mean /rods/beam/position?)" \
  "unknown observable path" "$BEAM" --out "$TMP/x" --sinewc "$SC" \
  --observable tip=/rods/bean/position[-1] --dt 100us
fails 4 "sinew-study: observable 'tip': index 21 of /rods/beam/position[21] out of range for axis 1 of size 21 (shape [1, 21, 3], first axis the frames)" \
  "index out of range" "$BEAM" --out "$TMP/x" --sinewc "$SC" --observable tip=/rods/beam/position[21] --dt 100us
fails 2 "sinew-study: --dt: unknown time unit 'uss' in '100uss' (did you mean 'us'?)" \
  "misspelt dt unit" "$BEAM" --out "$TMP/x" --observable "$TIP" --dt 100us,100uss
fails 2 "sinew-study: --dt: 'fast' is not a time (write e.g. '50ns' or '0.5s')" \
  "dt that is not a time" "$BEAM" --out "$TMP/x" --observable "$TIP" --dt fast
fails 2 "sinew-study: --dt: -1 us in '-1us' is not a positive time step" \
  "negative dt" "$BEAM" --out "$TMP/x" --observable "$TIP" --dt -1us
fails 2 "sinew-study: --integrator: unknown integrator 'pefr' (did you mean 'pefrl'?)" \
  "misspelt integrator" "$BEAM" --out "$TMP/x" --observable "$TIP" --dt 100us --integrator verlet,pefr
fails 2 "sinew-study: no output directory: give --out DIR" "no --out" "$BEAM" --observable "$TIP" --dt 100us
fails 2 "sinew-study: no time steps: give --dt LIST or --dt-factors LIST" "no dt" \
  "$BEAM" --out "$TMP/x" --observable "$TIP"
fails 2 "sinew-study: --observable: bad index '[-1,z]' in 'tip=/rods/beam/position[-1,z]': integers or ':' separated by commas (e.g. [-1] or [-1,2])" \
  "bad index syntax" "$BEAM" --out "$TMP/x" --observable 'tip=/rods/beam/position[-1,z]' --dt 100us
fails 2 "sinew-study: the reference run base verlet 1.5 ms became unstable at t = * ms: choose a smaller dt (--reference dt=...)" \
  "unstable reference" "$BEAM" --out "$TMP/x" --sinewc "$SC" --observable "$TIP" --dt 1.5ms
fails 2 "sinew-study: variant 'base': the simulator refused (exit 2): beam: --set: unknown param 'lod' (did you mean 'load'?)" \
  "a param the scene does not have" "$BEAM" --out "$TMP/x" --sinewc "$SC" --observable "$TIP" \
  --dt 100us --set lod=1N
fails 4 "sinew-study: variant 'odd' (--no-such-option): sinewc failed (exit 2): sinewc: unknown option '--no-such-option'" \
  "a variant that does not compile" "$BEAM" --out "$TMP/x" --sinewc "$SC" --observable "$TIP" \
  --dt 100us --variant odd:--no-such-option
fails 4 "sinew-study: $TMP/none.sinew: no such file" "missing scene" \
  "$TMP/none.sinew" --out "$TMP/x" --observable "$TIP" --dt 100us
fails 2 "sinew-study: unrecognized arguments: --dts 100us" "unknown option" \
  "$BEAM" --out "$TMP/x" --observable "$TIP" --dts 100us
done_testing
