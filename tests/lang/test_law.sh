#!/bin/sh
# test_law.sh — the constitutive law in the language:
#
#   variational = true in a material reaches every rod and muscle of that
#   material (the generated C sets rod.law / muscle.law = SW_LAW_VARIATIONAL
#   for exactly those), a rod or muscle may override its material's choice,
#   and a component parameter carries it (true or false, like rigid);
#   SIM --info names the law and the rods that take it;
#   models/human_arm.sinew's variational_law, set by sinewc --let on the
#   elbow, switches all of its 43 elastic rods, and a run of the elbow with
#   it keeps kinetic + elastic - work closer than Gazzola's law does over the
#   same 20 ms (the energy columns of the HDF5 output).
#
#   A muscle whose material says neither takes the variational law (issue
#   30: Gazzola's stiffens without bound as a filament shortens), a rod of
#   that material Gazzola's; `variational = false` on the material or on the
#   muscle keeps the reference's law.
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
SC=$SINEWC_CHECK
scratch law

cat >"$TMP/law.sinew" <<'MODEL'
material gel { E = 1 MPa; density = 1 g/cm^3; variational = true; }
material gum { E = 1 MPa; density = 1 g/cm^3; }
let exact = true;
component strand(y = 0 m, law = false) {
  rod fibre { material = gum; start = (0 m, y, 0 m); direction = (1, 0, 0); length = 5 cm;
          radius = 2 mm; elements = 5; variational = law; }
}
rod a { material = gel; start = (0, 0, 0) m; direction = (1, 0, 0); length = 5 cm;
        radius = 2 mm; elements = 5; }
rod b { material = gel; variational = false; start = (0, 1, 0) m; direction = (1, 0, 0);
        length = 5 cm; radius = 2 mm; elements = 5; }
use c = strand(2 m, law = exact);
use d = strand(3 m);
muscle e { material = gel; from = (0, 4, 0) m; to = (0.05, 4, 0) m; radius = 2 mm;
           filaments = 2; elements = 4; sigma_max = 1 MPa; }
clamp a.start;
simulate { duration = 1 ms; }
MODEL
"$SC" "$TMP/law.sinew" --emit-c -o "$TMP/law.c" 2>"$TMP/err"; ok $? "a model with both laws compiles"
diag <"$TMP/err"
# the definitions whose C sets the variational law: the name line before it
awk '/rod.name = |muscle.name = / { name = $3 } /\.law = SW_LAW_VARIATIONAL;/ { print name }' "$TMP/law.c" |
  tr -d '";' | tr '\n' ' ' >"$TMP/var"
[ "$(cat "$TMP/var")" = "a c.fibre e " ]; ok $? "variational: a (material), c.fibre (a let through a parameter), e (a muscle) (got: $(cat "$TMP/var"))"
"$SINEWC" "$TMP/law.sinew" -o "$TMP/law" 2>"$TMP/err"; ok $? "the model builds"
"$TMP/law" --info >"$TMP/info" 2>&1
grep -q '^constitutive law: variational (loads the gradient of the elastic energy) on 4 of 6 elastic rods: a, c.fibre, e.f01, e.f02; Gazzola et al. 2018 on the others$' "$TMP/info"
ok $? "SIM --info names the four variational rods (two are e's filaments)"
grep '^constitutive law' "$TMP/info" | diag
"$TMP/law" --quiet --out "$TMP/law.h5" >/dev/null 2>&1; ok $? "the model runs"

# ---- the default: the variational law for muscles, Gazzola's for rods
cat >"$TMP/default.sinew" <<'MODEL'
material soft { E = 10 kPa; density = 1.06 g/cm^3; }
material reference { E = 10 kPa; density = 1.06 g/cm^3; variational = false; }
rod strap { material = soft; start = (0, 0, 0) m; direction = (1, 0, 0); length = 5 cm;
            radius = 2 mm; elements = 5; }
muscle unsaid { material = soft; from = (0, 1, 0) m; to = (0.05, 1, 0) m; radius = 2 mm;
                filaments = 2; elements = 4; sigma_max = 300 kPa; }
muscle stated { material = reference; from = (0, 2, 0) m; to = (0.05, 2, 0) m; radius = 2 mm;
                filaments = 2; elements = 4; sigma_max = 300 kPa; }
muscle own { material = soft; variational = false; from = (0, 3, 0) m; to = (0.05, 3, 0) m;
             radius = 2 mm; filaments = 2; elements = 4; sigma_max = 300 kPa; }
muscle bare { E = 10 kPa; density = 1.06 g/cm^3; from = (0, 4, 0) m; to = (0.05, 4, 0) m;
              radius = 2 mm; filaments = 2; elements = 4; sigma_max = 300 kPa; }
simulate { duration = 1 ms; }
MODEL
"$SC" "$TMP/default.sinew" --emit-c -o "$TMP/default.c" 2>"$TMP/err"; ok $? "a model of both defaults compiles"
diag <"$TMP/err"
awk '/rod.name = |muscle.name = / { name = $3 } /\.law = SW_LAW_VARIATIONAL;/ { print name }' "$TMP/default.c" |
  tr -d '";' | tr '\n' ' ' >"$TMP/var"
[ "$(cat "$TMP/var")" = "unsaid bare " ]
ok $? "variational: the muscles whose material says neither (unsaid, bare); Gazzola's: the rod of that material (strap), the muscle of a material with variational = false (stated) and the muscle with its own (own) (got: $(cat "$TMP/var"))"
"$SINEWC" "$TMP/default.sinew" -o "$TMP/default" 2>"$TMP/err"; ok $? "it builds"
"$TMP/default" --info >"$TMP/info" 2>&1
grep -q '^constitutive law: variational (loads the gradient of the elastic energy) on 4 of 9 elastic rods: unsaid.f01, unsaid.f02, bare.f01, bare.f02; Gazzola et al. 2018 on the others$' "$TMP/info"
ok $? "SIM --info: the four filaments of unsaid and bare take the variational law, the others Gazzola's"
grep '^constitutive law' "$TMP/info" | diag

# ---- the elbow: Gazzola's law as written, the variational one by --let
E=examples/elbow_flexion.sinew
"$SINEWC" "$E" -o "$TMP/elbow_g" 2>"$TMP/err"; ok $? "the elbow builds"
"$TMP/elbow_g" --info | grep -q '^constitutive law: Gazzola et al. 2018 .*, all 43 elastic rods$'
ok $? "as written, the elbow's 43 elastic rods take Gazzola's law"
"$SINEWC" "$E" --let variational_law=true -o "$TMP/elbow_v" 2>"$TMP/err"; ok $? "--let variational_law=true builds"
"$TMP/elbow_v" --info | grep -q '^constitutive law: variational .* on 43 of 43 elastic rods: '
ok $? "with it, all 43 take the variational law"
for law in g v; do
  "$TMP/elbow_$law" --quiet --duration 20ms --every 1ms --out "$TMP/elbow_$law.h5" >/dev/null 2>&1
done
# kinetic + elastic - work over the run, against the largest work done
/usr/bin/python3 - "$TMP/elbow_g.h5" "$TMP/elbow_v.h5" >"$TMP/balance" 2>&1 <<'PY'
import sys, h5py, numpy as np
out = []
for path in sys.argv[1:]:
    e = h5py.File(path, "r")["/diagnostics/energy"][...]
    drift = e[:, 0] + e[:, 1] - e[:, 2] - (e[0, 0] + e[0, 1] - e[0, 2])
    out.append(np.max(np.abs(drift)) / np.max(np.abs(e[:, 2])))
print("elbow, 20 ms: max |kinetic + elastic - work| / max work: Gazzola %.3e, variational %.3e" % tuple(out))
sys.exit(0 if out[1] < 1e-3 and out[1] < out[0] else 1)
PY
ok $? "the variational elbow keeps its energy balance closer than Gazzola's"
diag <"$TMP/balance"
done_testing
