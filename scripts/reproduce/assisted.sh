#!/bin/sh
# assisted.sh — `make reproduce` module: the injured elbow assisted by an
# artificial muscle (Zhang et al. 2019, Suppl. Note 6.2, Fig. 7), by
# scripts/assisted_study.sh (`make assisted`): the healthy arm, the injured
# one, and the injured one with the AM releasing its twist at 0.25, 0.5 and
# 1 per second.  quick: 0.45 s of the reference's 0.7 s (the statements are
# tested from 0.2 s, past the ramps); full: 0.7 s.
#   scripts/reproduce/assisted.sh quick|full OUTDIR
set -eu
BUDGET=$1 OUT=$2
case $BUDGET in
  quick) sh scripts/assisted_study.sh --out "$OUT" --duration 0.45s ;;
  full) sh scripts/assisted_study.sh --out "$OUT" ;;
  *) echo "budget: quick or full" >&2; exit 2 ;;
esac
# the reference code's shear modulus for the AM's fibre, G = E / (1 + nu)
# (source/Polymer.cpp), against sinew's E / (2 (1 + nu)): the fastest
# release again with it
sed 's|^\(material am_fibre { E = 30 GPa; density = 1.67 g/cm^3;\) poisson = 0.5; }|\1 G = 20 GPa; }|' \
  examples/elbow_assisted.sinew > "$OUT/elbow_assisted_G.sinew"
grep -q 'G = 20 GPa' "$OUT/elbow_assisted_G.sinew"
SINEW_PATH=models ./bin/sinewc "$OUT/elbow_assisted_G.sinew" -o "$OUT/am_G"
case $BUDGET in quick) D="--duration 0.45s" ;; *) D= ;; esac
"$OUT/am_G" --quiet $D --set release_rate=1/s --out "$OUT/G_am_1.h5" > "$OUT/G_am_1.log" 2>&1 ||
  { echo "assisted.sh: the run with the reference's G stopped"; tail -3 "$OUT/G_am_1.log"; exit 1; }
for c in healthy injured am_0.25 am_0.5 am_1; do
  grep -q "stopped" "$OUT/$c.log" 2>/dev/null && { echo "assisted.sh: $c stopped"; tail -3 "$OUT/$c.log"; exit 1; }
done
/usr/bin/python3 scripts/reproduce/assisted_report.py "$OUT" "$BUDGET"
