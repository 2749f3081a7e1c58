#!/bin/sh
# bench_isa.sh [REPORT.md] — the rod step built for the two x86-64 levels
# and run side by side: bench_rod's cantilever (Verlet, one thread) from the
# runtime built at -march=x86-64-v3 (AVX2 and FMA: most laptops, AMD Zen 2
# and 3) and at -march=x86-64-v4 (AVX-512), both with GCC's generic tuning,
# so that on one CPU the one difference is the instruction set.  Each round
# runs every size once at each level, the levels alternating which goes
# first; the table gives the median over the rounds of each run's median
# batch, ns and cycles per element-step, and their ratio, against the
# target of issue 31 (v3 within 1.3 x the cycles of v4).  The v4 build runs
# only where the CPU has AVX-512 (bench_rod --cpu); elsewhere the section
# says so.  Written as the section "x86-64 levels" of REPORT.md
# (docs/benchmarks.md), which `make bench` runs.  SW_BENCH_ISA_ROUNDS (5)
# and SW_BENCH_ISA_SIZES ("25 50 100 200 400 800") change the run (~2 min).
set -eu
out=${1:-docs/benchmarks.md}
ROUNDS=${SW_BENCH_ISA_ROUNDS:-5}
SIZES=${SW_BENCH_ISA_SIZES:-"25 50 100 200 400 800"}
TARGET=1.3
title="x86-64 levels: AVX2 (x86-64-v3) and AVX-512 (x86-64-v4)"
make --no-print-directory build/bench/bench_rod >/dev/null
cpu=$(build/bench/bench_rod --cpu)
field() { echo "$cpu" | awk -v k="$1" '$1 == k { sub(/^[^ ]+ /, ""); print; exit }'; }
model=$(field model); avx2=$(field avx2); avx512f=$(field avx512f)
has_v3=$(field x86-64-v3); has_v4=$(field x86-64-v4)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
section=$tmp/section
{
  echo "Written by bench/bench_isa.sh, which \`make bench\` runs. The cantilever of"
  echo "\"Position Verlet\" above, from the runtime and bench_rod built twice:"
  echo "\`-O3 -march=x86-64-v3\` (AVX2, FMA: most laptops, AMD Zen 2 and 3) and"
  echo "\`-O3 -march=x86-64-v4\` (AVX-512), both with GCC's generic tuning, run on the"
  echo "same CPU. Each of $ROUNDS rounds runs every size once at each level"
  echo "(\`bench_rod_v3 --verlet N\`, \`bench_rod_v4 --verlet N\`), the two alternating"
  echo "which goes first; a run's figure is the median of its 9 batches, and the"
  echo "table gives the median of the $ROUNDS runs. Target (issue 31): the v3 build"
  echo "within $TARGET x the cycles per element-step of the v4 build."
  echo
  echo "- CPU: $model; avx2: $avx2, avx512f: $avx512f (x86-64-v3: $has_v3, x86-64-v4: $has_v4)."
  echo "- Compiler: $(${CC:-cc} --version | head -1)."
  echo "- Date: $(date -u '+%Y-%m-%d %H:%M UTC'); code: git $(git rev-parse --short HEAD 2>/dev/null || echo unknown)."
} > "$section"
if [ "$has_v3" != yes ]; then
  { echo; echo "This CPU does not run x86-64-v3 code (or is not an x86-64 CPU): neither build was run."; } >> "$section"
  python3 scripts/put_section.py "$out" "$title" "$(cat "$section")"
  cat "$section"
  exit 0
fi
levels=v3
[ "$has_v4" = yes ] && levels="v3 v4"
for l in $levels; do make --no-print-directory "build/bench/bench_rod_$l" >/dev/null; done
r=1
while [ "$r" -le "$ROUNDS" ]; do
  order=$levels
  [ $((r % 2)) -eq 0 ] && [ "$has_v4" = yes ] && order="v4 v3"
  for n in $SIZES; do
    for l in $order; do
      "build/bench/bench_rod_$l" --verlet "$n" 2>/dev/null > "$tmp/run"
      grep '^# cycles:' "$tmp/run" | head -1 > "$tmp/cycles"
      grep -v '^#' "$tmp/run" | awk -v l="$l" '{ print l, $0 }' >> "$tmp/rows"
    done
  done
  echo "bench_isa: round $r of $ROUNDS" >&2
  r=$((r + 1))
done
{
  echo "- Cycles:$(sed 's/^# cycles://' "$tmp/cycles")."
  [ "$has_v4" = yes ] || echo "- This CPU has no AVX-512: the x86-64-v4 build was not run."
  echo
} >> "$section"
# medians per level and size: level n ns ns_min cycles
awk -v sizes="$SIZES" -v v4="$has_v4" -v target="$TARGET" '
  function med(s,   a, k, i, j, t) {
    k = split(s, a, " ")
    for (i = 1; i <= k; i++) for (j = i + 1; j <= k; j++) if (a[j] + 0 < a[i] + 0) { t = a[i]; a[i] = a[j]; a[j] = t }
    return k % 2 ? a[(k + 1) / 2] : (a[k / 2] + a[k / 2 + 1]) / 2
  }
  { ns[$1, $2] = ns[$1, $2] " " $3; cy[$1, $2] = cy[$1, $2] " " $5 }
  END {
    k = split(sizes, n, " ")
    if (v4 == "yes") {
      print "| n | v3 ns/element-step | v4 ns/element-step | v3 cycles | v4 cycles | v3 / v4 (cycles) | within " target " x |"
      print "|--:|--:|--:|--:|--:|--:|:-:|"
    } else {
      print "| n | v3 ns/element-step | v3 cycles |"
      print "|--:|--:|--:|"
    }
    for (i = 1; i <= k; i++) {
      a = med(ns["v3", n[i]]); ca = med(cy["v3", n[i]]) + 0
      sa = ca > 0 ? sprintf("%.1f", ca) : "n/a"
      if (v4 != "yes") { printf "| %d | %.2f | %s |\n", n[i], a, sa; continue }
      b = med(ns["v4", n[i]]); cb = med(cy["v4", n[i]]) + 0
      sb = cb > 0 ? sprintf("%.1f", cb) : "n/a"
      ratio = ca > 0 && cb > 0 ? ca / cb : a / b   # no cycle counter: the ratio of the times
      printf "| %d | %.2f | %.2f | %s | %s | %.2f | %s |\n", n[i], a, b, sa, sb, ratio, ratio <= target ? "yes" : "no"
    }
  }' "$tmp/rows" >> "$section"
python3 scripts/put_section.py "$out" "$title" "$(cat "$section")"
cat "$section"
