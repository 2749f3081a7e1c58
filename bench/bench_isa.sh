#!/bin/sh
# bench_isa.sh [REPORT.md] — the rod step built for the two x86-64 levels
# and run side by side: bench_rod's cantilever (Verlet, one thread) from the
# runtime built at -march=x86-64-v3 (AVX2 and FMA: most laptops, AMD Zen 2
# and 3) and at -march=x86-64-v4 (AVX-512), both with GCC's generic tuning,
# so that on one CPU the one difference is the instruction set; and beside
# them the same two builds of the code of an earlier commit (by default git
# dbec346, the code before issue 31; built once in
# build/bench/isa-base-COMMIT-LEVEL from `git archive`, and measured with
# this tree's bench_rod.c).  Each round runs every size once in each build,
# the order alternating from round to round; the table gives the median over
# the rounds of each run's median batch, and the ratio of the v3 and v4
# cycles against the target of issue 31 (v3 within 1.3 x v4).  The v4
# builds run only where the CPU has AVX-512 (bench_rod --cpu); elsewhere the
# section says so.  Written as the section "x86-64 levels" of REPORT.md
# (docs/benchmarks.md), which `make bench` runs.  SW_BENCH_ISA_ROUNDS (5),
# SW_BENCH_ISA_SIZES ("25 50 100 200 400 800") and SW_BENCH_ISA_BASE (the
# commit; empty: no before columns) change the run (~5 min, and ~3 min
# more the first time, to build the code before).  The section ends with
# the subsection "aarch64": what GCC's vectorizer does with the same loops
# for 64-bit Arm (scripts/vec_report.sh --table, ~1 min; it installs the
# cross compiler when missing).
set -eu
out=${1:-docs/benchmarks.md}
ROUNDS=${SW_BENCH_ISA_ROUNDS:-5}
SIZES=${SW_BENCH_ISA_SIZES:-"25 50 100 200 400 800"}
BASE=${SW_BENCH_ISA_BASE-dbec346}   # the last commit before issue 31's loops
before_what=""
[ "$BASE" = dbec346 ] && before_what=", before issue 31"
TARGET=1.3
title="x86-64 levels: AVX2 (x86-64-v3) and AVX-512 (x86-64-v4)"
make --no-print-directory build/bench/bench_rod >/dev/null
cpu=$(build/bench/bench_rod --cpu)
field() { echo "$cpu" | awk -v k="$1" '$1 == k { sub(/^[^ ]+ /, ""); print; exit }'; }
model=$(field model); avx2=$(field avx2); avx512f=$(field avx512f)
has_v3=$(field x86-64-v3); has_v4=$(field x86-64-v4)
family=$(awk -F': *' '/^cpu family/ { print $2; exit }' /proc/cpuinfo 2>/dev/null || true)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
section=$tmp/section
{
  echo "Written by bench/bench_isa.sh, which \`make bench\` runs. The cantilever of"
  echo "\"Position Verlet\" above, from the runtime and bench_rod built at"
  echo "\`-O3 -march=x86-64-v3\` (AVX2, FMA: most laptops, AMD Zen 2 and 3) and at"
  echo "\`-O3 -march=x86-64-v4\` (AVX-512), both with GCC's generic tuning, run on the"
  if [ -n "$BASE" ]; then
    echo "same CPU; \"before\" is the same two builds of the code at git $BASE$before_what"
    echo "(measured with this tree's bench_rod.c). Each of $ROUNDS rounds runs every"
  else
    echo "same CPU (no earlier code was built: the \"before\" columns are empty). Each of $ROUNDS rounds runs every"
  fi
  echo "size once in each build (\`bench_rod_v3 --verlet N\`, ...), the order alternating"
  echo "from round to round; a run's figure is the median of its 9 batches, and the"
  echo "table gives the median of the $ROUNDS runs, ns and cycles per element-step."
  echo "Target (issue 31): the v3 build within $TARGET x the cycles of the v4 build."
  echo
  echo "- CPU: $model${family:+ (cpu family $family)}; avx2: $avx2, avx512f: $avx512f (x86-64-v3: $has_v3, x86-64-v4: $has_v4)."
  echo "- Compiler: $(${CC:-cc} --version | head -1)."
  echo "- Date: $(date -u '+%Y-%m-%d %H:%M UTC'); code: git $(git rev-parse --short HEAD 2>/dev/null || echo unknown)."
} > "$section"
if [ "$has_v3" != yes ]; then
  { echo; echo "This CPU does not run x86-64-v3 code (or is not an x86-64 CPU): no build was run."; } >> "$section"
  python3 scripts/put_section.py "$out" "$title" "$(cat "$section")"
  cat "$section"
  exit 0
fi
levels=v3
[ "$has_v4" = yes ] && levels="v3 v4"
builds=""
for l in $levels; do
  make --no-print-directory "build/bench/bench_rod_$l" >/dev/null
  # the code before, built once for this level by its own Makefile
  dir=build/bench/isa-base-$BASE-$l
  if [ -n "$BASE" ] && [ ! -f "$dir/build/libsinewrt.a" ]; then
    echo "bench_isa: building git $BASE at x86-64-$l in $dir" >&2
    rm -rf "$dir" && mkdir -p "$dir"
    if git archive "$BASE" | tar -x -C "$dir"; then
      make -C "$dir" --no-print-directory build/libsinewrt.a \
        CFLAGS="-O3 -march=x86-64-$l -fno-math-errno -fopenmp -g" >/dev/null || rm -f "$dir/build/libsinewrt.a"
    fi
  fi
  if [ -n "$BASE" ] && [ -f "$dir/build/libsinewrt.a" ]; then
    ${CC:-cc} -std=c11 -D_DEFAULT_SOURCE -O3 -march="x86-64-$l" -fno-math-errno -fopenmp -g \
      -I"$dir/runtime/include" $(pkg-config --cflags hdf5 gsl) bench/bench_rod.c \
      -o "build/bench/bench_rod_base_$l" "$dir/build/libsinewrt.a" $(pkg-config --libs hdf5 gsl) -lm
    builds="$builds base_$l"
  fi
  builds="$builds $l"
done
load0=$(cut -d' ' -f1 /proc/loadavg 2>/dev/null || echo unknown)
r=1
while [ "$r" -le "$ROUNDS" ]; do
  order=$builds
  [ $((r % 2)) -eq 0 ] && order=$(echo "$builds" | awk '{ for (i = NF; i > 0; i--) printf "%s ", $i }')
  for n in $SIZES; do
    for b in $order; do
      "build/bench/bench_rod_$b" --verlet "$n" 2>/dev/null > "$tmp/run"
      grep '^# cycles:' "$tmp/run" | head -1 > "$tmp/cycles"
      grep -v '^#' "$tmp/run" | awk -v b="$b" '{ print b, $0 }' >> "$tmp/rows"
    done
  done
  echo "bench_isa: round $r of $ROUNDS" >&2
  r=$((r + 1))
done
load1=$(cut -d' ' -f2 /proc/loadavg 2>/dev/null || echo unknown)
{
  echo "- Cycles:$(sed 's/^# cycles://' "$tmp/cycles")."
  echo "- Load average when the timing began (1 min): $load0; when it ended (5 min): $load1 ($(nproc) logical CPUs; each run is one thread)."
  [ "$has_v4" = yes ] || echo "- This CPU has no AVX-512: the x86-64-v4 builds were not run."
  echo
} >> "$section"
# medians per build and size, then one row per size
awk -v sizes="$SIZES" -v v4="$has_v4" -v target="$TARGET" -v base="$BASE" '
  function med(s,   a, k, i, j, t) {
    k = split(s, a, " ")
    if (k == 0) return -1
    for (i = 1; i <= k; i++) for (j = i + 1; j <= k; j++) if (a[j] + 0 < a[i] + 0) { t = a[i]; a[i] = a[j]; a[j] = t }
    return k % 2 ? a[(k + 1) / 2] : (a[k / 2] + a[k / 2 + 1]) / 2
  }
  function ns(b, n,   x) { x = med(t[b, n]); return x < 0 ? "—" : sprintf("%.2f", x) }
  function cyc(b, n,   x) { x = med(c[b, n]) + 0; return x > 0 ? sprintf("%.1f", x) : "n/a" }
  { t[$1, $2] = t[$1, $2] " " $3; c[$1, $2] = c[$1, $2] " " $5 }
  END {
    k = split(sizes, n, " ")
    if (v4 == "yes") {
      print "| n | v3 before (ns) | v3 (ns) | v4 before (ns) | v4 (ns) | v3 cycles | v4 cycles | v3 / v4 | within " target " x |"
      print "|--:|--:|--:|--:|--:|--:|--:|--:|:-:|"
    } else {
      print "| n | v3 before (ns) | v3 (ns) | v3 cycles |"
      print "|--:|--:|--:|--:|"
    }
    for (i = 1; i <= k; i++) {
      m = n[i]
      if (v4 != "yes") { printf "| %d | %s | %s | %s |\n", m, ns("base_v3", m), ns("v3", m), cyc("v3", m); continue }
      ca = med(c["v3", m]) + 0; cb = med(c["v4", m]) + 0
      ratio = ca > 0 && cb > 0 ? ca / cb : med(t["v3", m]) / med(t["v4", m])   # no cycle counter: the times
      printf "| %d | %s | %s | %s | %s | %s | %s | %.2f | %s |\n", m, ns("base_v3", m), ns("v3", m),
             ns("base_v4", m), ns("v4", m), cyc("v3", m), cyc("v4", m), ratio, ratio <= target ? "yes" : "no"
    }
  }' "$tmp/rows" >> "$section"
# the same loops for 64-bit Arm, compiled only (scripts/vec_report.sh --table)
{
  echo
  echo "### aarch64"
  echo
  echo "The step's files compiled (not run) for 64-bit Arm by Debian's cross compiler,"
  echo "$(aarch64-linux-gnu-gcc --version 2>/dev/null | head -1 || echo "aarch64-linux-gnu-gcc"), at the flags of \`make\` with"
  echo "\`-march=armv8-a\` (NEON: two doubles a vector, every 64-bit Arm) and"
  echo "\`-march=armv8.2-a+sve\` (SVE: vectors as long as the CPU makes them, \"variable\"),"
  echo "beside the two x86-64 levels above: for each function GCC emits, how many loops"
  echo "it vectorized and the widest vector (\`scripts/vec_report.sh --table\`, from"
  echo "\`-fopt-info-vec\`; a loop is counted in the function it was inlined into)."
  echo
  sh scripts/vec_report.sh --table
} >> "$section"
python3 scripts/put_section.py "$out" "$title" "$(cat "$section")"
cat "$section"
