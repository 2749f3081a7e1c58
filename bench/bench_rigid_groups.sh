#!/bin/sh
# bench_rigid_groups.sh — the scenes whose joints between rigid bodies are
# implicit (integrator = imex), built by the code that solved them as one
# dense system (git ed6d128, the last commit before issue 13's groups) and
# by this tree (a block per group, within its envelope: rigid_joint.c), run
# side by side for the same simulated time, interleaved, on one thread:
# wall seconds per simulated second (median of the runs), their ratio, and
# whether the two outputs agree bit for bit (scripts/compare_h5.py, the
# checkpoint /restart apart: it holds the system's workspace, whose size
# changed).  Written as the section "Implicit rigid joints (issue 13)" of
# docs/benchmarks.md.  The baseline is built from git in build/bench/
# base-$BASE (once, about a minute).  About 5 minutes with the defaults on
# this machine, most of it the baseline's 4- and 5-pair snakes.
set -eu
BASE=${SW_BENCH_BASE:-ed6d128}
RUNS=${SW_BENCH_RUNS:-5}
SIMT=${SW_BENCH_SIMT:-1}             # simulated seconds of each snake run
CHAIN_T=${SW_BENCH_CHAIN_T:-0.01}    # of the bone chain, at its 100x step
out=docs/benchmarks.md
dir=build/bench/base-$BASE
. bench/bench_base.sh
bench_base "$dir" "$BASE"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# scene name, source, sinewc's extra arguments, the simulator's
set -- \
  "snake_pairs1|examples/study/snake_pairs1.sinew||--duration $SIMT" \
  "snake_pairs2|examples/study/snake_pairs2.sinew||--duration $SIMT" \
  "snake_pairs3|examples/study/snake_pairs3.sinew||--duration $SIMT" \
  "snake_pairs4|examples/study/snake_pairs4.sinew||--duration $SIMT" \
  "snake_pairs5|examples/study/snake_pairs5.sinew||--duration $SIMT" \
  "snake_muscular|examples/snake_muscular.sinew||--duration $SIMT" \
  "bone_chain|examples/bone_chain.sinew|--let rigid_bones=true|--integrator imex --dt 81.1023ns --duration $CHAIN_T"
for s in "$@"; do
  IFS='|' read -r name src cargs sargs <<EOF
$s
EOF
  # shellcheck disable=SC2086
  "$dir/bin/sinewc" "$src" -o "$tmp/old_$name" $cargs
  # shellcheck disable=SC2086
  bin/sinewc "$src" -o "$tmp/new_$name" $cargs
done
wall() { # seconds of wall time of one run: wall SIMULATOR ARGS...
  sim=$1; shift
  s=$(date +%s.%N)
  # shellcheck disable=SC2068
  "$sim" --quiet --threads 1 --out "$sim.h5" $@ >/dev/null
  e=$(date +%s.%N)
  echo "$s $e" | awk '{ printf "%.6f\n", $2 - $1 }'
}
i=0
while [ $i -lt "$RUNS" ]; do
  for s in "$@"; do
    IFS='|' read -r name src cargs sargs <<EOF
$s
EOF
    if [ $((i % 2)) -eq 0 ]; then order="old new"; else order="new old"; fi
    for v in $order; do wall "$tmp/${v}_$name" "$sargs" >> "$tmp/${v}_$name.t"; done
  done
  i=$((i + 1))
done
med() { sort -g "$1" | awk '{ a[NR] = $1 } END { print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2 }'; }
rows=$(mktemp)
for s in "$@"; do
  IFS='|' read -r name src cargs sargs <<EOF
$s
EOF
  # shellcheck disable=SC2086
  info=$("$tmp/new_$name" --info $sargs | sed -n 's/.*rigid bodies (\([0-9]*\) bod[a-z]* in \([0-9]*\) independent group.*/\1 \2/p')
  t=$(echo "$sargs" | sed 's/.*--duration \([0-9.e-]*\).*/\1/')
  same=$(/usr/bin/python3 scripts/compare_h5.py "$tmp/old_$name.h5" "$tmp/new_$name.h5" --except restart || true)
  awk -v n="$name" -v i="$info" -v o="$(med "$tmp/old_$name.t")" -v w="$(med "$tmp/new_$name.t")" \
      -v t="$t" -v same="$same" 'BEGIN { split(i, b, " ")
    printf "| %s | %d (%d) | %d | %.2f | %.2f | %.2f | %s |\n", n, b[1], 6 * b[1], b[2], o / t, w / t, o / w, same }' >> "$rows"
done
section=$(mktemp)
{
  echo "Written by bench/bench_rigid_groups.sh (\`make bench\`). Under \`integrator = imex\`"
  echo "the joints between rigid bodies are solved by one linear system per kick"
  echo "(docs/physics.md, \"Joints between rigid bodies\"). The code before issue 13's"
  echo "groups (git $BASE) factored it whole, dense; this tree (git $(git rev-parse --short HEAD)$(git diff --quiet HEAD -- runtime compiler || echo ', with uncommitted changes in runtime/ or compiler/'))"
  echo "factors each independent group's block on its own, within its envelope"
  echo "(rigid_joint.c). Each scene built by both, run $RUNS times on one thread for"
  echo "$SIMT s of simulated time (the bone chain, rigid bones at 100x its explicit step:"
  echo "$CHAIN_T s), old and new interleaved run by run; wall time includes start-up"
  echo "and output. \"Outputs\": every dataset of the two runs' files compared"
  echo "(scripts/compare_h5.py, the checkpoint apart). Machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'),"
  echo "$(nproc) logical CPUs, $(date -u '+%Y-%m-%d %H:%M UTC'), load average $(cut -d' ' -f1-3 /proc/loadavg) at the end."
  echo
  echo "| scene | rigid bodies in the system (unknowns) | groups | wall s per simulated s, one dense system | per group | x | outputs |"
  echo "|---|--:|--:|--:|--:|--:|---|"
  cat "$rows"
  echo
  echo "The snakes gain from the groups (each rib with its two tendons, 18 unknowns,"
  echo "touches no other rigid body), more the more pairs they have: the whole's cost"
  echo "grew as the cube of the bodies, the groups' grows as their number. The bone"
  echo "chain is one group; it gains from the envelope (each bone's rows reach back"
  echo "one bone, so its factor is a band)."
} > "$section"
/usr/bin/python3 scripts/put_section.py "$out" "Implicit rigid joints (issue 13)" "$(cat "$section")"
rm -f "$rows" "$section"
cat "$out" | sed -n '/^## Implicit rigid joints (issue 13)/,/^## [^I]/p'
