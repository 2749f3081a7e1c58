#!/bin/sh
# test_imex.sh — integrator = imex in the simulate block: the generated C
# hands the runtime SW_IMEX (verlet and pefrl their own), the compiler's
# runtime check accepts it, and the simulator reports it in --info, treats
# the muscle filaments' Hill damping implicitly and runs.
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
SC=$SINEWC_CHECK
scratch imex

M=examples/constructs/imex.sinew
"$SC" "$M" --emit-c -o "$TMP/imex.c" 2>"$TMP/err"; ok $? "$M compiles to C"
diag <"$TMP/err"
grep -q '^  sw_spec_set_integrator(s, SW_IMEX);$' "$TMP/imex.c"; ok $? "the C sets SW_IMEX"
# the same scene with each of the other words
for w in verlet:SW_VERLET pefrl:SW_PEFRL; do
  sed "s/integrator = imex;/integrator = ${w%%:*};/" "$M" >"$TMP/other.sinew"
  "$SC" "$TMP/other.sinew" --emit-c -o "$TMP/other.c" 2>"$TMP/err" &&
    grep -q "^  sw_spec_set_integrator(s, ${w#*:});$" "$TMP/other.c"
  ok $? "integrator = ${w%%:*} sets ${w#*:}"
done
sed "s/ integrator = imex;//" "$M" >"$TMP/other.sinew"
"$SC" "$TMP/other.sinew" --emit-c -o "$TMP/other.c" 2>"$TMP/err" &&
  grep -q '^  sw_spec_set_integrator(s, SW_VERLET);$' "$TMP/other.c"
ok $? "without an integrator, SW_VERLET"

"$SINEWC" "$M" -o "$TMP/imex" 2>"$TMP/err"; ok $? "$M builds"
diag <"$TMP/err"
"$TMP/imex" --info >"$TMP/info" 2>&1
grep -q '^integrator: position Verlet, stiff terms linearly implicit (imex)$' "$TMP/info"
ok $? "--info: integrator: position Verlet, stiff terms linearly implicit (imex)"
grep -q '^  linearly implicit: the Hill damping of 6 of 6 muscle filaments$' "$TMP/info"
ok $? "--info: the Hill damping of the six filaments is implicit"
grep '^integrator' -A3 "$TMP/info" | diag
(cd "$TMP" && ./imex --quiet --duration 5ms --out imex.h5) >"$TMP/err" 2>&1; ok $? "it runs 5 ms"
diag <"$TMP/err"
done_testing
