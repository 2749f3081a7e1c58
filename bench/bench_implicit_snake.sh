#!/bin/sh
# bench_implicit_snake.sh — the hardened snakes of Zhang et al. 2019 (Suppl.
# Fig. 10: shear and twist x25; Figs. 11-12: x100) on flat ground for 10 s,
# explicit (position Verlet at 0.9 of the snake's own stable estimate, 31 us
# and 12 us) against implicit rods (integrator = imex, the body's elasticity
# by the trapezoidal rule, rod_implicit.c) at 125 us, a step the original
# snake's explicit scheme takes.  Runs are interleaved, REPEAT times each;
# the table gives median wall times, the ratio, and the differences in
# forward speed and lateral excursion over 2-10 s and the grid-scale share
# of the strains.  Writes the section "Implicit rods: the hardened snakes
# (issue 9)" of docs/benchmarks.md.
set -e
OUT=build/bench/implicit_snake
REPEAT=${REPEAT:-3}
DUR=${DUR:-10s}
mkdir -p $OUT
export SINEW_PATH=models
./bin/sinewc examples/snake_hardening.sinew -o $OUT/explicit
./bin/sinewc --let implicit=true examples/snake_hardening.sinew -o $OUT/implicit
estimate() { # SIM args... -> the stable estimate from --info, as "31.0492us"
  "$@" --info | sed -n 's/^dt: .*stable estimate \([0-9.e+-]*\) \([a-z]*\)).*/\1\2/p'
}
scaled() { # "31.0492us" FACTOR -> "27.9443us"
  v=$(echo "$1" | sed 's/[a-z]*$//'); u=$(echo "$1" | sed 's/^[0-9.e+-]*//')
  printf '%.6g%s' "$(echo "$v * $2" | bc -l)" "$u"
}
wall() { # OUT SIM args... -> seconds of wall time
  out=$1; shift
  s=$(date +%s.%N)
  "$@" --quiet --out "$out" --duration $DUR >/dev/null
  e=$(date +%s.%N)
  echo "$e - $s" | bc
}
: > $OUT/walls.txt
for f in 25 100; do
  E=$(estimate $OUT/explicit --set shear=$f --set twist=$f)
  DT=$(scaled "$E" 0.9)
  echo "x$f explicit_dt $DT" >> $OUT/walls.txt
  for k in $(seq $REPEAT); do
    echo "x$f explicit $(wall $OUT/explicit_$f.h5 $OUT/explicit --set shear=$f --set twist=$f --dt $DT)" >> $OUT/walls.txt
    echo "x$f implicit $(wall $OUT/implicit_$f.h5 $OUT/implicit --set shear=$f --set twist=$f --integrator imex --dt 125us)" >> $OUT/walls.txt
  done
done
wall $OUT/original.h5 $OUT/explicit --set shear=1 --set twist=1 --dt 125us > $OUT/original.wall
REPORT=$(/usr/bin/python3 scripts/implicit_snake_report.py $OUT "$DUR")
echo "$REPORT"
/usr/bin/python3 scripts/put_section.py docs/benchmarks.md "Implicit rods: the hardened snakes (issue 9)" "$REPORT"
