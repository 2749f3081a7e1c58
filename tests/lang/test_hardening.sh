#!/bin/sh
# test_hardening.sh — the twist and shear hardening params of the walker and
# the flagella swimmer (Zhang et al. 2019, Suppl. Notes 6.3 and 6.4;
# scripts/reproduce/walker.sh and swimmer.sh run them) reach the right rods.
# --info prints a hardened rod's G: it must be the factor times the
# material's G = 2E/3 computed here from the scene's E (walker scaffold
# 319.4 kPa, muscle 10 kPa; swimmer substrate 3.86 MPa, cell 30 kPa), on the
# rods of that part only; and the hardening acts on the stiffness the step
# is estimated from: no hardened rod's stable dt rises, at least one's falls
# (a rod whose step another mode limits keeps it: the swimmer's tail under
# twist), and the other rods' do not move.  --info only: a few seconds.
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
scratch hardening

# rodline INFO ROD: the rod's --info line
rodline() { grep "^  $2: " "$1"; }
# g_of LINE KIND: the G that LINE prints for shear or twist ("" if none)
g_of() { echo "$1" | sed -n "s/.*$2 G x[0-9.e+]* = \([0-9.e+-]*\) Pa.*/\1/p"; }
# dt_of LINE: the stable dt in seconds
dt_of() { echo "$1" | awk '{ for (i = 1; i < NF; i++) if ($i == "dt") {
  u = $(i + 2); sub(/,$/, "", u); s = u == "ns" ? 1e-9 : u == "us" ? 1e-6 : u == "ms" ? 1e-3 : 1;
  printf "%.9g", $(i + 1) * s; exit } }'; }
# close A B: |A - B| <= 1e-3 |B| (--info prints 4 digits)
close() { awk -v a="$1" -v b="$2" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(b != 0 && d <= 1e-3 * (b < 0 ? -b : b)) }'; }
below() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a < b) }'; }

# check SIM KIND FACTOR G_MATERIAL HARDENED_RODS OTHER_RODS SET...
check() {
  sim=$1 kind=$2 f=$3 g=$4 hard=$5 other=$6; shift 6
  "$sim" --info > "$TMP/base" 2>/dev/null
  "$sim" --info "$@" > "$TMP/hard" 2>/dev/null; ok $? "$(basename "$sim") --info $*"
  want=$(awk -v f="$f" -v g="$g" 'BEGIN { printf "%.6g", f * g }')
  fell=0
  for r in $hard; do
    l=$(rodline "$TMP/hard" "$r"); got=$(g_of "$l" "$kind")
    close "${got:-0}" "$want"; ok $? "$r: $kind G = ${got:-none} Pa, want $f x $g = $want Pa"
    d0=$(dt_of "$(rodline "$TMP/base" "$r")"); d1=$(dt_of "$l")
    ! below "$d0" "$d1"; ok $? "$r: stable dt $d0 s before, $d1 s after"
    below "$d1" "$d0" && fell=$((fell + 1))
  done
  [ $fell -ge 1 ]; ok $? "the stable dt of $fell of the hardened rods falls"
  for r in $other; do
    l=$(rodline "$TMP/hard" "$r")
    [ -z "$(g_of "$l" shear)$(g_of "$l" twist)" ]; ok $? "$r: not hardened"
    d0=$(dt_of "$(rodline "$TMP/base" "$r")"); d1=$(dt_of "$l")
    [ "$d0" = "$d1" ]; ok $? "$r: stable dt stays $d0 s ($d1 s)"
  done
}

"$SINEWC" examples/walker.sinew -o "$TMP/walker" 2>"$TMP/err"; ok $? "sinewc builds the walker"
diag < "$TMP/err"
SCAF="rear.foot_l front.foot_r rear.post_l front.bar beam_r"
RING="ring.f01 ring.f02"
gs=$(awk 'BEGIN { printf "%.9g", 2 * 319.4e3 / 3 }')
gm=$(awk 'BEGIN { printf "%.9g", 2 * 10e3 / 3 }')
check "$TMP/walker" shear 1e4 "$gs" "$SCAF" "$RING" --set scaffold_shear=1e4
check "$TMP/walker" twist 1e4 "$gs" "$SCAF" "$RING" --set scaffold_twist=1e4
"$TMP/walker" --info --set muscle_shear=10 --set muscle_twist=10 > "$TMP/m" 2>/dev/null
for r in $RING; do
  l=$(rodline "$TMP/m" "$r")
  close "$(g_of "$l" shear)" "$(awk -v g="$gm" 'BEGIN { print 10 * g }')" &&
    close "$(g_of "$l" twist)" "$(awk -v g="$gm" 'BEGIN { print 10 * g }')"
  ok $? "$r: muscle_shear, muscle_twist = 10: G x10 = $(g_of "$l" shear), $(g_of "$l" twist) Pa"
done
for r in $SCAF; do
  l=$(rodline "$TMP/m" "$r"); [ -z "$(g_of "$l" shear)$(g_of "$l" twist)" ]
  ok $? "$r: the muscle's factors leave the scaffold alone"
done

"$SINEWC" examples/flagella_swimmer.sinew -o "$TMP/swimmer" 2>"$TMP/err"; ok $? "sinewc builds the swimmer"
diag < "$TMP/err"
gp=$(awk 'BEGIN { printf "%.9g", 2 * 3.86e6 / 3 }')
gc=$(awk 'BEGIN { printf "%.9g", 2 * 30e3 / 3 }')
check "$TMP/swimmer" shear 100 "$gp" "head tail" "cell.f01" --set shear=100
check "$TMP/swimmer" twist 100 "$gp" "head tail" "cell.f01" --set twist=100
check "$TMP/swimmer" shear 100 "$gc" "cell.f01" "head tail" --set cell_shear=100
"$TMP/swimmer" --info --set cell_twist=100 > "$TMP/c" 2>/dev/null
l=$(rodline "$TMP/c" cell.f01)
close "$(g_of "$l" twist)" "$(awk -v g="$gc" 'BEGIN { print 100 * g }')"
ok $? "cell.f01: cell_twist = 100: twist G = $(g_of "$l" twist) Pa"
for r in head tail post_front; do
  l=$(rodline "$TMP/c" "$r"); [ -z "$(g_of "$l" shear)$(g_of "$l" twist)" ]
  ok $? "$r: the cell's factor leaves the substrate alone"
done
done_testing
