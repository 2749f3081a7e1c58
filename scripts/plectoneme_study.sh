#!/bin/sh
# plectoneme_study.sh — `make plectoneme`: the twisted rod under tension that
# buckles into a plectoneme (issue 34; docs/validation.md, "Self-contact: the
# plectoneme"), from examples/plectoneme.sinew.
#
#   scripts/plectoneme_study.sh [--out DIR]
#
# Runs (DIR, default build/plectoneme, gets RUN.h5, RUN.json, RUN.csv):
#   thick_40, thick_80, thick_160   r = 5 mm, n = 50, L sqrt(F/B) = 4, its
#                                   end turned 4 turns in 40, 80, 160 s, then
#                                   held 10 s: the torque-twist curve and the
#                                   buckling delay against the twisting rate
#   control_40                      thick_40 without self-contact (stiffness
#                                   1e-9 N/m): the rod passes through itself
#   thin                            r = 2.5 mm, n = 100, L sqrt(F/B) = 6,
#                                   damping 0.075 kg/m/s (the thick rod's
#                                   damping time rho A / gamma), 6 turns in
#                                   80 s, held 20 s: a longer ply
#   vthin                           r = 1.25 mm, n = 150, L sqrt(F/B) = 8,
#                                   damping 0.003 kg/m/s, 7 turns in 70 s,
#                                   held 15 s: longer still
# then docs/img/plectoneme.png and DIR/plectoneme.md
# (scripts/plectoneme_report.py).  A run whose .json exists is not made
# again.  About 30 min on this machine's 2 cores (vthin 20 of them), two
# runs at a time.
set -eu
ROOT=$(cd "$(dirname "$0")/.." && pwd)
OUT=build/plectoneme
while [ $# -gt 0 ]; do
  case $1 in
    --out) OUT=$2; shift 2 ;;
    *) echo "plectoneme_study.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
mkdir -p "$OUT"
MODEL="$ROOT/examples/plectoneme.sinew"
PY=/usr/bin/python3
SC="$ROOT/bin/sinewc"
for tt in 40 80 160; do
  "$SC" --let n=50 --let radius=5mm --let twist_time=${tt}s --let hold=10s "$MODEL" -o "$OUT/thick_$tt"
done
"$SC" --let n=100 --let radius=2.5mm --let twist_time=80s --let hold=20s "$MODEL" -o "$OUT/thin"
"$SC" --let n=150 --let radius=1.25mm --let twist_time=70s --let hold=15s "$MODEL" -o "$OUT/vthin"

run() {   # run NAME BINARY ARGS...: the run, then its analysis
  name=$1; bin=$2; shift 2
  [ -s "$OUT/$name.json" ] && return 0
  "$OUT/$bin" --quiet --out "$OUT/$name.h5" "$@" >"$OUT/$name.log" 2>&1
  "$PY" "$ROOT/scripts/plectoneme.py" "$OUT/$name.h5" --quiet --crossings-every 5 \
    --csv "$OUT/$name.csv" --json "$OUT/$name.json" >>"$OUT/$name.log" 2>&1
  echo "plectoneme_study: $name done"
}
run vthin vthin --set turns=7 --set tension=0.12272mN --set damp=0.003kg/m/s &
run thick_160 thick_160 --set turns=4
run thick_40 thick_40 --set turns=4
run thick_80 thick_80 --set turns=4
run control_40 thick_40 --set turns=4 --set kc=1e-9N/m
run thin thin --set turns=6 --set tension=1.1045mN --set damp=0.075kg/m/s
wait
"$PY" "$ROOT/scripts/plectoneme_report.py" "$OUT" --plot "$ROOT/docs/img/plectoneme.png" >"$OUT/plectoneme.md"
cat "$OUT/plectoneme.md"
