#!/bin/sh
# test_let.sh — switches and compile-time lets:
#
#   true and false held by a let and by a component parameter (default and
#   argument) reach rigid: the generated C sets rod.rigid = 1 for exactly
#   those rods, and SIM --info lists them as held rigid;
#   sinewc --let NAME=VALUE changes the compiled model (element counts,
#   rigid bones, a length with its unit) as editing the let would: build()
#   is the same as for the edited file; the overrides are recorded in the
#   generated C's header, at the end of model_source (with .sha256 its hash)
#   and so in the HDF5 output's model_source and model_sha256;
#   usage errors of --let give one line and exit 2 (the exact messages are
#   golden files, tests/lang/errors/let_*).
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
SC=$SINEWC_CHECK
scratch let
LIBS="$ROOT/build/libsinewrt.a $(pkg-config --libs hdf5 gsl 2>/dev/null) -lm"
CFLAGS_RT="-I$ROOT/runtime/include $(pkg-config --cflags hdf5 gsl 2>/dev/null)"

# ---- true and false through a let and a component parameter
cat >"$TMP/switch.sinew" <<'MODEL'
material bone_tissue { E = 15 GPa; density = 1.75 g/cm^3; }
let held = true;
component limb(x = 0 m, stiff = false) {
  bone upper { material = bone_tissue; start = (x, 0 m, 0 m); direction = (0, 0, -1);
               length = 10 cm; radius = 5 mm; elements = 4; rigid = stiff; }
  clamp upper.start;
}
use a = limb(0 m, stiff = held);     # a let, through an argument
use b = limb(1 m);                   # the default, false
use c = limb(2 m, stiff = true);     # the word itself
bone d { material = bone_tissue; start = (3, 0, 0) m; direction = (0, 0, -1);
         length = 10 cm; radius = 5 mm; elements = 4; rigid = held; }
clamp d.start;
simulate { duration = 1 ms; }
MODEL
"$SC" "$TMP/switch.sinew" --emit-c -o "$TMP/switch.c" 2>"$TMP/err"; ok $? "true and false through lets and component parameters compile"
diag <"$TMP/err"
n=$(grep -c 'rod.rigid = 1;' "$TMP/switch.c")
[ "$n" -eq 3 ]; ok $? "the C sets rod.rigid = 1 for three of the four rods ($n)"
# the rigid rods are a.upper, c.upper and d: the line after each rod's name
awk '/rod.name = / { name = $3 } /rod.rigid = 1;/ { print name }' "$TMP/switch.c" | tr -d '";' |
  tr '\n' ' ' >"$TMP/rigid"
[ "$(cat "$TMP/rigid")" = "a.upper c.upper d " ]; ok $? "held rigid: a.upper, c.upper, d (got: $(cat "$TMP/rigid"))"
"$SINEWC" "$TMP/switch.sinew" -o "$TMP/switch" 2>"$TMP/err"; ok $? "the switch model builds"
"$TMP/switch" --info >"$TMP/info" 2>&1
grep -q '^  held rigid (one body each, no elastic waves): 3 rods: a.upper, c.upper, d$' "$TMP/info"
ok $? "SIM --info holds a.upper, c.upper and d rigid"
grep -q '^  b.upper: 4 elements, .*stable dt [0-9.]* [a-z]*$' "$TMP/info"; ok $? "b.upper (the default false) stays elastic"

# ---- the elbow as written: elastic bones, 20/7/14 elements
E=examples/elbow_flexion.sinew
"$SC" "$E" --emit-c -o "$TMP/elbow.c" 2>"$TMP/err"; ok $? "the elbow compiles"
diag <"$TMP/err"
! grep -q 'rod.rigid = 1;' "$TMP/elbow.c"; ok $? "as written, no bone is rigid"
! grep -q 'Compiled with sinewc --let\|# ---- sinewc --let' "$TMP/elbow.c"; ok $? "without --let the C records no override"

# ---- --let changes the compiled model
"$SC" "$E" --let rigid_bones=true --let bone_elements=10 --let tendon_elements=5 \
  --let muscle_elements=8 --emit-c -o "$TMP/let.c" 2>"$TMP/err"
ok $? "the elbow compiles with four --let"
diag <"$TMP/err"
[ "$(grep -c 'rod.rigid = 1;' "$TMP/let.c")" -eq 3 ]; ok $? "--let rigid_bones=true: the three bones are rigid"
"$SINEWC" "$E" --let rigid_bones=true --let bone_elements=10 --let tendon_elements=5 \
  --let muscle_elements=8 -o "$TMP/let" 2>"$TMP/err"; ok $? "the overridden elbow builds"
"$TMP/let" --info >"$TMP/info" 2>&1
grep -q '^  arm.humerus: 10 elements, .*, rigid$' "$TMP/info"; ok $? "--info: arm.humerus has 10 elements and is rigid"
grep -q '^  arm.long_proximal: 5 elements' "$TMP/info"; ok $? "--info: a tendon has 5 elements"
grep -q '^  arm.biceps_long.f01: 8 elements' "$TMP/info"; ok $? "--info: a filament has 8 elements"
grep -q '^  held rigid (one body each, no elastic waves): 3 rods: arm.humerus, arm.ulna, arm.radius$' "$TMP/info"
ok $? "--info: the three bones are held rigid"

# ---- the same as editing the lets: build() and main() equal but for the
# source and its hash (both compiled from one directory, so paths match)
mkdir "$TMP/a" "$TMP/b"
cp "$E" "$TMP/a/model.sinew"
sed -e 's/^let rigid_bones = false;/let rigid_bones = true; /' -e 's/^let bone_elements = 20;/let bone_elements = 10;/' \
  "$E" >"$TMP/b/model.sinew"
(cd "$TMP/a" && "$SC" model.sinew --let rigid_bones=true --let bone_elements=10 --emit-c -o ../a.c) 2>"$TMP/err"
ok $? "the copy compiles with --let"
(cd "$TMP/b" && "$SC" model.sinew --emit-c -o ../b.c) 2>>"$TMP/err"; ok $? "the edited copy compiles"
diag <"$TMP/err"
code() { sed -n '/^static const swParam params/,$p' "$1" | grep -v '\.sha256 = '; }
code "$TMP/a.c" >"$TMP/a.code"; code "$TMP/b.c" >"$TMP/b.code"
cmp -s "$TMP/a.code" "$TMP/b.code"; ok $? "--let gives the C of the edited model"
diff "$TMP/a.code" "$TMP/b.code" | head -20 | diag

# ---- provenance: the header of the C, model_source and its hash
grep -q '^ \*   --let rigid_bones=true   (the let at model.sinew:16)$' "$TMP/a.c" &&
  grep -q '^ \*   --let bone_elements=10   (the let at model.sinew:17)$' "$TMP/a.c"
ok $? "the C's header comment lists the overrides and their lets"
grep -q '^  "# --let rigid_bones=true (in place of the let at line 16)\\n"$' "$TMP/a.c" &&
  grep -q '^  "# --let bone_elements=10 (in place of the let at line 17)\\n"' "$TMP/a.c"
ok $? "model_source ends with the overrides"
# print model_source of the generated C and hash it
cat >"$TMP/source.c" <<'PROG'
#define main generated_main
#include "a.c"
#undef main
int main(void) { return fputs(model_source, stdout) < 0; }
PROG
# shellcheck disable=SC2086
"${CC:-cc}" -std=c11 -fopenmp $CFLAGS_RT -I"$TMP" "$TMP/source.c" -o "$TMP/source" $LIBS 2>"$TMP/err"
ok $? "a program printing the generated model_source builds"
diag <"$TMP/err"
"$TMP/source" >"$TMP/source.txt"
sum=$(sha256sum <"$TMP/source.txt" | cut -d' ' -f1)
grep -q "\.sha256 = \"$sum\"" "$TMP/a.c"; ok $? "model_sha256 is the hash of model_source with its overrides ($sum)"
tail -n 3 "$TMP/source.txt" | diag
(cd "$TMP/a" && "$SC" model.sinew --let rigid_bones=true --let bone_elements=10 -o sim) 2>"$TMP/err"
ok $? "the overridden copy builds"
(cd "$TMP/a" && ./sim --quiet --duration 2us --out run.h5) >"$TMP/err" 2>&1; ok $? "it runs"
diag <"$TMP/err"
h5dump -a /model_sha256 "$TMP/a/run.h5" 2>/dev/null | grep -q "\"$sum\""; ok $? "the HDF5 output's model_sha256 is that hash"
h5dump -a /model_source "$TMP/a/run.h5" 2>/dev/null | grep -q -- '--let bone_elements=10 (in place of the let at line 17)'
ok $? "the HDF5 output's model_source records the overrides"

# ---- a length with its unit
cat >"$TMP/span.sinew" <<'MODEL'
material tissue { E = 1 MPa; density = 1.1 g/cm^3; }
let span = 20 cm;
rod beam { material = tissue; start = (0, 0, 0) m; direction = (1, 0, 0); length = span;
           radius = 5 mm; elements = 10; }
clamp beam.start;
simulate { duration = 1 ms; }
MODEL
"$SC" "$TMP/span.sinew" --let span=3cm --emit-c -o "$TMP/span.c" 2>"$TMP/err"; ok $? "--let span=3cm compiles"
diag <"$TMP/err"
grep -q '^    rod.length = 0.03;$' "$TMP/span.c"; ok $? "the rod is 3 cm long"
"$SC" "$TMP/span.sinew" --let "span=1.5 mm" --emit-c -o "$TMP/span.c" 2>"$TMP/err" &&
  grep -q '^    rod.length = 0.0015;$' "$TMP/span.c"
ok $? "--let 'span=1.5 mm': a blank between number and unit"

# ---- usage errors: one line, exit 2
usage_error() {   # usage_error DESCRIPTION EXPECTED-LINE ARGS...
  what=$1 want=$2
  shift 2
  "$SC" --check "$@" >"$TMP/out" 2>"$TMP/err"
  rc=$?
  [ $rc -eq 2 ] && [ "$(wc -l <"$TMP/err")" -eq 1 ] && [ "$(cat "$TMP/err")" = "$want" ]
  ok $? "$what (exit $rc)"
  [ "$(cat "$TMP/err")" = "$want" ] || diag <"$TMP/err"
}
usage_error "--let without a value" "sinewc: --let needs NAME=VALUE" "$TMP/span.sinew" --let
usage_error "--let without '='" "sinewc: --let: expected NAME=VALUE, got 'span'" "$TMP/span.sinew" --let span
usage_error "--let given twice" "sinewc: --let span is given twice ('span=1cm' and 'span=2cm')" \
  "$TMP/span.sinew" --let span=1cm --let span=2cm
grep -v '^let span' "$TMP/span.sinew" | sed 's/length = span;/length = 20 cm;/' >"$TMP/nolets.sinew"
usage_error "a model with no lets of its own" \
  "sinewc: --let: unknown let 'span' ($TMP/nolets.sinew has no top-level lets)" "$TMP/nolets.sinew" --let span=1cm
"$SC" --check "$E" --let biceps_sigma_max=1Pa >"$TMP/out" 2>"$TMP/err"
[ $? -eq 2 ] && [ "$(wc -l <"$TMP/err")" -eq 1 ] &&
  grep -q "^sinewc: --let biceps_sigma_max: 'biceps_sigma_max' is a let of .*models/human_arm.sinew:[0-9]*, not a top-level let of $E\$" "$TMP/err"
ok $? "a let of an imported file is no top-level let of the model (exit 2)"
diag <"$TMP/err"
"$SC" --check "$TMP/span.sinew" --let span=0cm >"$TMP/out" 2>"$TMP/err"
[ $? -eq 1 ] && grep -q "'length' must be positive, got 0 m" "$TMP/err"
ok $? "a value of the right kind that the model refuses is a model error (exit 1)"

done_testing
