#!/bin/sh
# test_wrap.sh — wrapping by contact (examples/constructs/wrap.sinew): a
# muscle pulled with 5 N over a cylinder of 2 cm carried by a clamped bone
# and centred on the joint's axis, while the other bone turns about that
# axis at 2 rad/s from 90 to 213 deg; its moment arm about the joint, from
# the torque of its distal tie (|(I - c) x F| / |F|) and from its path
# (dL/dalpha), against the closed-form geodesic (docs/physics.md, "Wrapping
# over a cylinder"): |r x u| while the straight line clears the cylinder,
# R_eff = R + rho (rho the muscle's radius) while it wraps, within an a
# priori bound (penalty sink T dphi / k, polygon R dphi^2 / 8, a dynamic
# allowance), and the path length against tangents + R_eff x wrap angle.
# The same muscle through two via points gives the polygon's moment arm
# R_v cos(gamma / 2).  Convergence: with a stiff contact the error falls
# with the elements (order > 1), with 48 elements the sink falls as 1/k.
# scripts/wrap_analysis.py has the closed forms and the checks.
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
scratch wrap

ex=examples/constructs/wrap.sinew
for n in 24 12 48; do
  "$SINEWC_CHECK" $ex --let muscle_elements=$n -o "$TMP/wrap$n" 2>"$TMP/err$n"
  ok $? "the scene compiles with $n elements a muscle"
  diag <"$TMP/err$n"
done
run() {   # run N K: the scene with N elements and contact stiffness K N/m
  "$TMP/wrap$1" --quiet --set contact_stiffness="$2 N/m" --out "$TMP/w_$1_$2.h5" >"$TMP/run" 2>&1
  ok $? "it runs its sweep with $1 elements, k = $2 N/m"
  diag <"$TMP/run"
}
run 24 1e4; run 12 1e5; run 48 1e3; run 48 1e4; run 48 1e5

/usr/bin/python3 - "$ROOT/scripts" "$TMP" >"$TMP/checks" 2>&1 <<'PY'
import sys
sys.path.insert(0, sys.argv[1])
import wrap_analysis as w
t = sys.argv[2]
runs = {(n, k): "%s/w_%d_%.0e.h5" % (t, n, k) for n, k in ((12, 1e5), (48, 1e3), (48, 1e4), (48, 1e5))}
runs = {key: p.replace("e+0", "e") for key, p in runs.items()}
for passed, msg in w.checks(t + "/w_24_1e4.h5", runs):
    print("PASS" if passed else "FAIL", msg)
PY
grep -q '^\(PASS\|FAIL\)' "$TMP/checks" || { ok 1 "the analysis ran"; diag <"$TMP/checks"; }
while read -r verdict msg; do
  case $verdict in
    PASS) ok 0 "$msg" ;;
    FAIL) ok 1 "$msg" ;;
    *) echo "$verdict $msg" | diag ;;
  esac
done <"$TMP/checks"
done_testing
