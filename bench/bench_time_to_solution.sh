#!/bin/sh
# bench_time_to_solution.sh — time to solution of Zhang et al. 2019's studies
# (issue 31): each scene compiled, its step checked against a quarter of it on
# a window of the simulated time, and run for its whole simulated time at that
# step (the swimmer and the walker, minutes each: estimated from the window).
# scripts/tts_report.py runs the simulators and writes the section "Time to
# solution (issue 31)" of docs/benchmarks.md.  About 8 minutes of CPU (16 of
# wall time on a shared machine).  TTS_REUSE=1 keeps the runs of an
# interrupted pass (their commands and times in build/bench/tts/commands.txt).
set -e
OUT=build/bench/tts
mkdir -p $OUT
export SINEW_PATH=models
for s in elbow_flexion elbow_hardening elbow_isometric elbow_isokinetic \
         snake_continuum snake_muscular flagella_swimmer walker; do
  ./bin/sinewc examples/$s.sinew -o $OUT/$s
done
./bin/sinewc examples/elbow_flexion.sinew --let implicit_bones=true --let implicit_tendons=true \
  -o $OUT/elbow_flexion_imp
./bin/sinewc examples/snake_hardening.sinew --let implicit=true -o $OUT/snake_hardening_imp
./bin/sinewc examples/snake_terrain.sinew -o $OUT/snake_terrain
./bin/sinewc examples/study/snake_pairs4.sinew -o $OUT/snake_pairs4
/usr/bin/python3 scripts/tts_report.py $OUT docs/benchmarks.md
/usr/bin/python3 scripts/put_section.py docs/benchmarks.md "Time to solution (issue 31)" "$(cat $OUT/section.md)"
