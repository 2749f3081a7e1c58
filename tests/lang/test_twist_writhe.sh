#!/bin/sh
# test_twist_writhe.sh — Calugareanu-White-Fuller on the discrete rod:
# examples/twist_writhe.sinew twists a soft rod through 27 rad (2 Greenhill
# critical twists for clamped ends) between a clamp and an end turned by a
# prescribed angular velocity, then brings the end 20 cm closer without
# turning it, then holds it.  scripts/sinew-link computes each frame's
# twist Tw (discrete, by parallel transport of d1 along the centreline
# polygon), writhe Wr (Gauss's double integral over the rod closed by
# straight extensions along the end tangents and a far planar loop, summed
# pair by pair as Klenin & Langowski 2000) and link Lk = Tw + Wr.
#
#   twisting  while the end turns, Lk follows the prescribed rotation:
#             Lk(5 s) = 27 rad / 2 pi (the table's 1 ms ramp-down adds
#             half a millisecond of it)
#   writhing  from 5.1 s on (ends fixed in orientation) Lk stays within
#             1e-6 turns while the writhe grows past 0.3 turns and the twist
#             falls by as much; every frame's closed ribbon has an integer
#             link (the script checks it to 1e-6: directors consistent with
#             the centreline)
. "$(dirname "$0")/tap.sh"
scratch twist_writhe
PY=/usr/bin/python3
LINK="$ROOT/scripts/sinew-link"

"$SINEWC_CHECK" "$ROOT/examples/twist_writhe.sinew" -o "$TMP/tw" >"$TMP/out" 2>&1
rc=$?; ok $rc "twist_writhe.sinew compiles"
[ $rc -eq 0 ] || diag <"$TMP/out"
(cd "$TMP" && ./tw --quiet --out tw.h5) >"$TMP/out" 2>&1
rc=$?; ok $rc "twist_writhe runs 15 s"
[ $rc -eq 0 ] || diag <"$TMP/out"

"$PY" "$LINK" "$TMP/tw.h5" --rod strand --end element --csv "$TMP/link.csv" --quiet >"$TMP/out" 2>&1
rc=$?; ok $rc "sinew-link reads the run; every frame's closed ribbon has an integer link"
[ $rc -eq 0 ] || diag <"$TMP/out"

"$PY" - "$TMP/link.csv" >"$TMP/out" 2>&1 <<'PYEOF'
import math, sys
import numpy as np
r = np.loadtxt(sys.argv[1], delimiter=",", skiprows=1)
t, tw, wr, lk = r[:, 0], r[:, 1], r[:, 2], r[:, 3]
k5 = np.argmin(abs(t - 5.0))
want = 27.0 / (2 * math.pi)
print(f"twisting: Lk(5 s) = {lk[k5]:.9f} turns, prescribed {want:.9f}, error {lk[k5] - want:.2e}")
sys.exit(0 if abs(lk[k5] - want) < 1e-6 else 1)
PYEOF
rc=$?; ok $rc "twisting: Lk follows the end's prescribed rotation"
diag <"$TMP/out"

"$PY" "$LINK" "$TMP/tw.h5" --rod strand --end element --quiet --check-lk 1e-6 --after 5.1 >"$TMP/out" 2>&1
rc=$?; ok $rc "writhing: Lk = Tw + Wr held within 1e-6 turns with the ends fixed"
diag <"$TMP/out"

"$PY" - "$TMP/link.csv" >"$TMP/out" 2>&1 <<'PYEOF'
import sys
import numpy as np
r = np.loadtxt(sys.argv[1], delimiter=",", skiprows=1)
t, tw, wr = r[:, 0], r[:, 1], r[:, 2]
a, z = np.argmin(abs(t - 5.1)), -1
print(f"twist into writhe: Tw {tw[a]:.6f} -> {tw[z]:.6f}, Wr {wr[a]:.6f} -> {wr[z]:.6f} turns "
      f"(Tw_kappa from the curvature at the end: {r[z, 4]:.6f})")
sys.exit(0 if wr[z] > 0.3 and abs((tw[a] - tw[z]) - (wr[z] - wr[a])) < 1e-6 else 1)
PYEOF
rc=$?; ok $rc "writhing: more than 0.3 turns of twist become writhe"
diag <"$TMP/out"

done_testing
