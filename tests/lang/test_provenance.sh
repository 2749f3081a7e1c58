#!/bin/sh
# test_provenance.sh — model_sha256 identifies the model, not the machine:
#
#   the elbow compiled from two copies of the tree in different directories,
#   its models found along SINEW_PATH once absolute and once relative, gives
#   the same generated C byte for byte, with no path of either copy in it,
#   and the same model_sha256; a run in each writes files whose root
#   attributes (model_source, model_sha256, ...) are equal and name neither
#   directory; changing the imported file changes the hash, and an equal
#   change made in both copies changes it equally.
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
SC=$SINEWC_CHECK
scratch provenance

mkdir -p "$TMP/one/tree" "$TMP/two/deeper/tree"
for d in "$TMP/one/tree" "$TMP/two/deeper/tree"; do cp -r examples models "$d/"; done
(cd "$TMP/one/tree" && SINEW_PATH="$TMP/one/tree/models" "$SC" "$TMP/one/tree/examples/pendulum.sinew" \
  --emit-c -o "$TMP/one.c") 2>"$TMP/err"
ok $? "the pendulum compiles from the first copy, by absolute paths"
(cd "$TMP/two/deeper/tree/examples" && SINEW_PATH=../models "$SC" elbow_flexion.sinew \
  --emit-c -o "$TMP/two_elbow.c") 2>>"$TMP/err"
ok $? "the elbow compiles from the second copy, by relative paths"
(cd "$TMP/one/tree" && SINEW_PATH="$TMP/one/tree/models" "$SC" \
  "$TMP/one/tree/examples/elbow_flexion.sinew" --emit-c -o "$TMP/one_elbow.c") 2>>"$TMP/err"
ok $? "and from the first"
diag <"$TMP/err"
cmp -s "$TMP/one_elbow.c" "$TMP/two_elbow.c"; ok $? "the two generated C files are the same bytes"
n=$(grep -c "$TMP" "$TMP/one_elbow.c" "$TMP/one.c" | awk -F: '{ s += $2 } END { print s }')
ok $((n != 0)) "no path of the tree is in the generated C ($n lines)"

for w in one two/deeper; do
  (cd "$TMP/$w/tree/examples" && SINEW_PATH=../models "$SC" elbow_flexion.sinew \
    -o "$TMP/sim_$(echo $w | tr / _)") 2>>"$TMP/err" || echo "compile failed in $w" >>"$TMP/err"
done
"$TMP/sim_one" --duration 1us --out "$TMP/one.h5" --quiet && "$TMP/sim_two_deeper" \
  --duration 1us --out "$TMP/two.h5" --quiet
ok $? "a run in each"
diag <"$TMP/err"
/usr/bin/python3 - "$TMP/one.h5" "$TMP/two.h5" "$TMP" >"$TMP/py" 2>&1 <<'PY'
import sys, h5py
a, b, tmp = h5py.File(sys.argv[1]), h5py.File(sys.argv[2]), sys.argv[3]
def text(v):
    return v.decode() if isinstance(v, bytes) else str(v)
for k in a.attrs:
    if k == "status":
        continue
    assert text(a.attrs[k]) == text(b.attrs[k]), k
    assert tmp not in text(a.attrs[k]), k
print("model_sha256", text(a.attrs["model_sha256"]), "over", len(a.attrs), "attributes")
PY
ok $? "the files' root attributes are equal and name neither directory"
diag <"$TMP/py"

sha() { "$1" --info | awk '/sha256:/ { print $2 }'; }
h1=$(sha "$TMP/sim_one")
[ "$(sha "$TMP/sim_two_deeper")" = "$h1" ]; ok $? "the two simulators report the same model_sha256"
printf '\n# a comment changes the text\n' >>"$TMP/one/tree/models/human_arm.sinew"
(cd "$TMP/one/tree/examples" && SINEW_PATH=../models "$SC" elbow_flexion.sinew -o "$TMP/sim_one") \
  2>>"$TMP/err"
h2=$(sha "$TMP/sim_one")
[ -n "$h1" ] && [ "$h1" != "$h2" ]; ok $? "a changed import changes the hash ($h1 -> $h2)"
printf '\n# a comment changes the text\n' >>"$TMP/two/deeper/tree/models/human_arm.sinew"
(cd "$TMP/two/deeper/tree/examples" && SINEW_PATH=../models "$SC" elbow_flexion.sinew \
  -o "$TMP/sim_two_deeper") 2>>"$TMP/err"
[ "$(sha "$TMP/sim_two_deeper")" = "$h2" ]; ok $? "the same change in the other copy gives the same hash"

done_testing
