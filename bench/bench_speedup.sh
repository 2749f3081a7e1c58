#!/bin/sh
# bench_speedup.sh — the elbow (examples/elbow_flexion.sinew) built by the code
# before issue 10 and by this tree, run side by side at the same fixed dt for
# the same simulated time, interleaved, on one thread; wall seconds per
# simulated second (median of the runs) and their ratio, written as the
# section "Speed-up on the elbow" of docs/benchmarks.md.  The baseline is
# built from git in build/bench/base (once; its own Makefile and flags).
set -eu
BASE=${SW_BENCH_BASE:-d25e385}      # last commit before the layout of issue 10
SIMT=${SW_BENCH_SIMT:-0.02}         # simulated seconds per run
RUNS=${SW_BENCH_RUNS:-9}
DT=${SW_BENCH_DT:-668ns}            # the scene's own dt (half its stable estimate)
out=docs/benchmarks.md
dir=build/bench/base
. bench/bench_base.sh
bench_base "$dir" "$BASE"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$dir/bin/sinewc" examples/elbow_flexion.sinew -o "$tmp/old"
bin/sinewc examples/elbow_flexion.sinew -o "$tmp/new"
bin/sinewc --portable examples/elbow_flexion.sinew -o "$tmp/portable"
wall() { # seconds of wall time of one run: wall SIMULATOR [THREADS]
  s=$(date +%s.%N)
  "$1" --quiet --threads "${2:-1}" --dt "$DT" --duration "$SIMT" --every "$SIMT" --out "$tmp/o.h5" >/dev/null
  e=$(date +%s.%N)
  echo "$s $e" | awk '{ printf "%.6f\n", $2 - $1 }'
}
i=0
while [ $i -lt "$RUNS" ]; do
  for v in old new portable; do wall "$tmp/$v" >> "$tmp/$v.t"; done
  wall "$tmp/new" 2 >> "$tmp/new2.t"
  i=$((i + 1))
done
med() { sort -g "$1" | awk '{ a[NR] = $1 } END { print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2 }'; }
mo=$(med "$tmp/old.t"); mn=$(med "$tmp/new.t"); mp=$(med "$tmp/portable.t"); m2=$(med "$tmp/new2.t")
section=$(mktemp)
{
  echo "## Speed-up on the elbow (issue 10)"
  echo
  echo "Written by bench/bench_speedup.sh, which \`make bench\` runs. The elbow"
  echo "(examples/elbow_flexion.sinew: 43 rods, 592 elements, 79 joints, two muscles"
  echo "of 18 filaments) built by the code before issue 10 (git $BASE, its own Makefile:"
  echo "runtime and simulator at -O2 for the x86-64 baseline) and by this tree (git"
  echo "$(git rev-parse --short HEAD), runtime and simulator at -O3 -march=native; and with"
  echo "\`sinewc --portable\`), each run $RUNS times for $SIMT s of simulated time at dt = $DT on"
  echo "one thread (the native build also on two, --threads 2), the four interleaved run by"
  echo "run. Wall time includes start-up and"
  echo "writing two frames. Machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'), $(date -u '+%Y-%m-%d %H:%M UTC')."
  echo
  echo "| build | wall s per simulated s (median) | x before |"
  echo "|---|--:|--:|"
  awk -v o="$mo" -v n="$mn" -v p="$mp" -v n2="$m2" -v t="$SIMT" 'BEGIN {
    printf "| before issue 10 | %.1f | 1.00 |\n", o / t
    printf "| this tree, native | %.1f | %.2f |\n", n / t, o / n
    printf "| this tree, native, --threads 2 | %.1f | %.2f |\n", n2 / t, o / n2
    printf "| this tree, --portable | %.1f | %.2f |\n", p / t, o / p }'
} > "$section"
# replace the section if it is there, else append it
awk -v f="$section" '
  /^## Speed-up on the elbow/ { skip = 1; while ((getline l < f) > 0) print l; print ""; next }
  skip && /^## / { skip = 0 }
  !skip { print }' "$out" > "$tmp/md"
grep -q '^## Speed-up on the elbow' "$out" || { echo; cat "$section"; } >> "$tmp/md"
cp "$tmp/md" "$out"
cat "$section"
rm -f "$section"
