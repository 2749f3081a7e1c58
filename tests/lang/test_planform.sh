#!/bin/sh
# test_planform.sh — the area a fluid's rods show, as --info reports it
# (runtime/engine/planform.c), against closed forms:
#   vane     9 parallel rods of length L = 100 mm, radius r = 1 mm, 2r apart
#            (side by side, no gap): planform 9 x 2r x L = 1800 mm^2, and
#            the silhouettes sum to the same
#   doubled  the same vane twice, the copy 5 mm above it: the planform is
#            still 1800 mm^2 (overlaps once), the silhouettes 3600
#   cross    two rods of 2r x L crossing at right angles at their middles,
#            turned 45 deg to the grid:
#            2 x 2rL - (2r)^2 = 396 mm^2
#   spaced   9 rods 4r apart: 1800 mm^2 again (the gaps are not counted)
# and rod lists that name a loop (every pass's rods) or an instance.
. "$(dirname "$0")/tap.sh"
scratch planform

vane() { # vane FILE EXTRA-ITEMS FLUID-RODS SPACING
  cat > "$1" <<MODEL
material film { E = 1 MPa; density = 1000 kg/m^3; }
component sheet(z, gap) {
  for strip[k] in (0, 8) {
    rod bar { material = film; start = (k * gap, 0 mm, z); direction = (0, 1, 0); normal = (0, 0, 1);
            length = 100 mm; radius = 1 mm; elements = 10; }
  }
}
use lower = sheet(0 mm, $4);
$2
fluid air { model = quadratic; density = 1.2 kg/m^3; drag_coefficient = 1.2; rods = $3; }
simulate { duration = 1 ms; }
MODEL
}

area() { # area FILE: "planform error silhouette" in mm^2 from --info
  "$SINEWC" "$1" -o "$TMP/sim" 2>"$TMP/cc.err" || { cat "$TMP/cc.err" >&2; return 1; }
  "$TMP/sim" --info > "$TMP/info" || return 1
  sed -n 's/.*planform \([0-9.e+-]*\) m^2 (+- \([0-9.e+-]*\);.*silhouettes \([0-9.e+-]*\) m^2.*/\1 \2 \3/p' "$TMP/info" |
    awk '{ printf "%.6g %.6g %.6g\n", $1 * 1e6, $2 * 1e6, $3 * 1e6 }'
}

near() { # near GOT WANT REL: |GOT - WANT| <= REL WANT
  awk -v g="$1" -v w="$2" -v r="$3" 'BEGIN { d = g - w; if (d < 0) d = -d; exit !(d <= r * w) }'
}

vane "$TMP/vane.sinew" "" "lower" "2 mm"
set -- $(area "$TMP/vane.sinew")
echo "# vane: planform $1 mm^2 (+- $2), silhouettes $3 mm^2; closed form 1800 both"
near "$1" 1800 0.005; ok $? "9 strips side by side: planform within 0.5% of 9 x 2r x L = 1800 mm^2 (got $1)"
near "$3" 1800 1e-9; ok $? "their silhouettes sum to 2rL each, 1800 mm^2 (got $3)"

vane "$TMP/double.sinew" "use upper = sheet(5 mm, 2 mm);" "(lower, upper.strip)" "2 mm"
set -- $(area "$TMP/double.sinew")
echo "# doubled: planform $1 mm^2, silhouettes $3 mm^2; closed form 1800 and 3600"
near "$1" 1800 0.005; ok $? "the vane doubled 5 mm above itself: overlaps counted once (got $1)"
near "$3" 3600 1e-9; ok $? "the silhouettes count both (got $3)"

cat > "$TMP/cross.sinew" <<'MODEL'
material film { E = 1 MPa; density = 1000 kg/m^3; }
rod a { material = film; start = (-35.355, -35.355, 0) mm; direction = (1, 1, 0); normal = (0, 0, 1);
        length = 100 mm; radius = 1 mm; elements = 10; }
rod b { material = film; start = (35.355, -35.355, 0) mm; direction = (-1, 1, 0); normal = (0, 0, 1);
        length = 100 mm; radius = 1 mm; elements = 10; }
fluid air { model = quadratic; density = 1.2 kg/m^3; drag_coefficient = 1.2; }
simulate { duration = 1 ms; }
MODEL
set -- $(area "$TMP/cross.sinew")
echo "# cross: planform $1 mm^2 (+- $2); closed form 396"
near "$1" 396 0.005; ok $? "two strips crossing: 2 x 2rL - (2r)^2 = 396 mm^2 within 0.5% (got $1)"
sed -n 's/.*normal (\([^)]*\)).*/\1/p' "$TMP/info" | tr -d ' ' |
  awk -F, '{ z = $3 < 0 ? -$3 : $3; up = z > 0.999 } END { exit !up }'
ok $? "their mean plane is z = 0"

vane "$TMP/spaced.sinew" "rod spare { material = film; start = (0, 0, 1) m; direction = (1, 0, 0); length = 10 mm; radius = 1 mm; elements = 2; }" "lower.strip" "4 mm"
set -- $(area "$TMP/spaced.sinew")
echo "# spaced: planform $1 mm^2; closed form 1800"
near "$1" 1800 0.005; ok $? "strips 4r apart: the gaps are not counted (got $1)"
grep -q '9 rods, lower.strip\[0\].bar ... lower.strip\[8\].bar' "$TMP/info"
ok $? "a loop in a rod list stands for the rods of all its passes (the spare rod left out)"

vane "$TMP/bad.sinew" "let q = 1;" "(lower, q)" "2 mm"
"$SINEWC_CHECK" --check "$TMP/bad.sinew" 2>"$TMP/bad.err"
grep -q "lists rods, muscles, instances and loops (or all), not a value" "$TMP/bad.err"
ok $? "a let in a rod list is refused, naming what a rod list takes"
diag < "$TMP/bad.err"

done_testing
