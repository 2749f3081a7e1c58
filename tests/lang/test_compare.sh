#!/bin/sh
# test_compare.sh — SIM --compare GOLDEN.h5 [--rtol R]: a run against a
# stored one, dataset by dataset:
#
#   the same run matches its golden file (every dataset, exit 0); a run with
#   another param differs, each differing dataset named with its largest
#   difference in its units and the first frame it exceeds the tolerance
#   (exit 5); --rtol loose enough accepts it; a run of fewer frames differs
#   in shape; a dataset the golden file has and the run has not fails; a
#   missing golden file is an I/O error (exit 4) before the run; comparing
#   with the file the run would write, or --rtol without --compare, is a
#   usage error (exit 2).
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
SC=$SINEWC_CHECK
scratch compare

"$SC" examples/pendulum.sinew -o "$TMP/p" 2>"$TMP/err"; ok $? "the pendulum compiles"
diag <"$TMP/err"
"$TMP/p" --duration 20ms --out "$TMP/golden.h5" --quiet 2>"$TMP/err"; ok $? "a golden run"
"$TMP/p" --duration 20ms --out "$TMP/same.h5" --compare "$TMP/golden.h5" 2>"$TMP/run"; rc=$?
ok $rc "the same run matches it (exit $rc)"
grep -q '^p: compare: 6 datasets match, 0 differ$' "$TMP/run"; ok $? "all six datasets match"
diag <"$TMP/run"

"$TMP/p" --duration 20ms --set release=10.1deg --out "$TMP/other.h5" --compare "$TMP/golden.h5" \
  --quiet 2>"$TMP/run"; rc=$?
ok $((rc != 5)) "another release angle differs (exit $rc)"
diag <"$TMP/run"
grep -Eq '^    FAILED /joints/pivot/angle: differs by up to [0-9.e+-]+ rad \([0-9.e+-]+ of its largest value, [0-9.e+-]+ rad\), first at frame 1$' "$TMP/run"
ok $? "a differing dataset is named with its difference in its units and the first frame"
grep -q '^p: compare: 2 datasets match, 4 differ$' "$TMP/run"; ok $? "the summary counts them (time and the node radii match)"
"$TMP/p" --duration 20ms --set release=10.1deg --out "$TMP/other.h5" --compare "$TMP/golden.h5" \
  --rtol 0.5 --quiet 2>"$TMP/run"; rc=$?
ok $rc "--rtol 0.5 accepts it (exit $rc)"

"$TMP/p" --duration 10ms --out "$TMP/short.h5" --compare "$TMP/golden.h5" --quiet 2>"$TMP/run"
rc=$?
ok $((rc != 5)) "a shorter run differs (exit $rc)"
grep -q '^    FAILED /time: shape \[11\], the golden file'"'"'s \[21\]$' "$TMP/run"
ok $? "in shape, both shapes given"

/usr/bin/python3 - "$TMP/golden.h5" "$TMP/extra.h5" <<'PY' 2>&1 | diag
import shutil, sys, h5py
shutil.copy(sys.argv[1], sys.argv[2])
with h5py.File(sys.argv[2], "a") as f:
    f["/probes/extra"] = [[1.0, 2.0, 3.0]]
PY
"$TMP/p" --duration 20ms --out "$TMP/x.h5" --compare "$TMP/extra.h5" --quiet 2>"$TMP/run"; rc=$?
ok $((rc != 5)) "a dataset only the golden file has fails (exit $rc)"
grep -q '^    FAILED /probes/extra: not in the run'"'"'s file$' "$TMP/run"; ok $? "and is named"

"$TMP/p" --duration 1ms --out "$TMP/y.h5" --compare "$TMP/none.h5" 2>"$TMP/run"; rc=$?
ok $((rc != 4)) "a missing golden file: exit 4 (got $rc)"
grep -q "^p: --compare: cannot read '$TMP/none.h5': No such file or directory$" "$TMP/run"
ok $? "named"
[ ! -e "$TMP/y.h5" ]; ok $? "before the run writes anything"
"$TMP/p" --out "$TMP/golden.h5" --compare "$TMP/golden.h5" 2>"$TMP/run"; rc=$?
ok $((rc != 2)) "comparing with the file the run would write: exit 2 (got $rc)"
diag <"$TMP/run"
"$TMP/p" --rtol 1e-3 2>"$TMP/run"; rc=$?
ok $((rc != 2)) "--rtol without --compare: exit 2 (got $rc)"
"$TMP/p" --compare "$TMP/golden.h5" --rtol lots 2>"$TMP/run"; rc=$?
ok $((rc != 2)) "--rtol that is no number: exit 2 (got $rc)"
diag <"$TMP/run"

done_testing
