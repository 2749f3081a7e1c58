#!/bin/sh
# vec_report.sh [--aarch64] [MARCH] — what GCC's vectorizer did with the hot
# loops of the step (rod.c, integrate.c, loads.c, muscle.c, stability.c) at
# the flags of `make`, for -march=MARCH (native unless given; x86-64-v3 and
# x86-64-v4 are the levels `make bench` compares): each loop of those files
# that it vectorized, with the vector width, as -fopt-info-vec-optimized
# reports it.  Printed as Markdown for docs/performance.md ("What the
# vectorizer did").
#
# --aarch64: the same files compiled (not run) by Debian's cross compiler
# aarch64-linux-gnu-gcc (package gcc-aarch64-linux-gnu, installed by
# scripts/deps.sh when missing, with libc6-dev-arm64-cross, its C headers),
# MARCH armv8-a unless given (NEON, 16-byte vectors, what every 64-bit Arm
# has) or e.g. armv8.2-a+sve (SVE, vectors of
# a length the CPU chooses: "variable length").
# --table: one Markdown table, for docs/benchmarks.md (bench/bench_isa.sh):
# each function of those files in which x86-64-v3, x86-64-v4, armv8-a or
# armv8.2-a+sve vectorizes a loop, with how many and the widest vector at
# each ("—": every loop scalar there).
set -eu
files="runtime/engine/rod.c runtime/engine/integrate.c runtime/engine/loads.c runtime/engine/muscle.c runtime/engine/stability.c"
opts="-std=c11 -D_DEFAULT_SOURCE -O3 -fno-math-errno -fopenmp"
cross=aarch64-linux-gnu-gcc
need_cross() {
  sh scripts/deps.sh gcc-aarch64-linux-gnu:/usr/bin/$cross \
    libc6-dev-arm64-cross:/usr/aarch64-linux-gnu/include/stdio.h # a recommendation only
}
# the vectorized loops of file $3 by compiler $1 at -march=$2, one line each:
# "file:line:col: optimized: ..." (runtime/ stripped), sorted
vectorized() {
  "$1" $opts -march="$2" -Iruntime/include -Iruntime -fopt-info-vec-optimized -c "$3" -o /dev/null 2>&1 |
    grep 'loop vectorized' | sed 's|^runtime/||' | sort -t: -k1,1 -k2,2n -u
}
# the function line $2 of runtime/$1 is in (for a loop whose first statement
# was inlined from vec.h, the report names vec.h)
function_of() {
  awk -v n="$2" 'NR <= n && /^[a-z].*[a-z_0-9]+\((const|int|double|void|sw)/ { f = $0 }
    END { match(f, /[a-z_0-9]+\((const|int|double|void|sw)/); f = substr(f, RSTART, RLENGTH);
          sub(/\(.*/, "", f); print f }' "runtime/$1"
}

if [ "${1:-}" = --table ]; then
  # GCC attributes a vectorized loop to the line of its first statement,
  # which is vec.h's for a loop that starts with an inlined helper at one
  # level and not at another, so the table counts loops by the function GCC
  # emitted them in (its note "vectorized N loops in function", after the
  # function's loops): N and the widest vector used (a narrower one in the
  # same function is a vectorized remainder)
  need_cross
  tmp=$(mktemp -d)
  trap 'rm -rf "$tmp"' EXIT
  for t in "${CC:-cc} x86-64-v3" "${CC:-cc} x86-64-v4" "$cross armv8-a" "$cross armv8.2-a+sve"; do
    set -- $t
    for f in $files; do
      "$1" $opts -march="$2" -Iruntime/include -Iruntime -fopt-info-vec-all -c "$f" -o /dev/null 2>&1 |
        grep -E 'optimized: loop vectorized|note: vectorized [0-9]+ loops in function' | sed 's|^runtime/||' |
        awk -F: -v t="$2" '
          /loop vectorized/ { w = $0; sub(/.*using /, "", w); sub(/ vectors.*/, "", w)
                              b = w == "variable length" ? 1000 : w + 0
                              if (b > best) { best = b; width = w == "variable length" ? "variable" : b "-byte" } }
          /loops in function/ { k = $0; sub(/.*vectorized /, "", k); sub(/ loops.*/, "", k)
                                if (k > 0) print $1 "\t" $2 "\t" t "\t" k " x " width
                                best = 0; width = "" }'
    done
  done > "$tmp/all"
  # the emitted function's name from the line its note names
  while IFS="$(printf '\t')" read -r file line target cell; do
    printf '%s\t%s\t%s\n' "$file: $(function_of "$file" "$line")" "$target" "$cell"
  done < "$tmp/all" > "$tmp/named"
  echo "| function: loops vectorized (as GCC counts them: a loop's versions and vectorized remainders apart) x widest vector | x86-64-v3 | x86-64-v4 | armv8-a | armv8.2-a+sve |"
  echo "|---|:-:|:-:|:-:|:-:|"
  cut -f1 "$tmp/named" | awk '!seen[$0]++' | while read -r fn; do
    row="| $fn"
    for t in x86-64-v3 x86-64-v4 armv8-a armv8.2-a+sve; do
      c=$(awk -F'\t' -v f="$fn" -v t="$t" '$1 == f && $2 == t { print $3; exit }' "$tmp/named")
      row="$row | ${c:-—}"
    done
    echo "$row |"
  done
  exit 0
fi

cc=${CC:-cc}
march=native
if [ "${1:-}" = --aarch64 ]; then
  need_cross
  cc=$cross
  march=armv8-a
  shift
fi
march=${1:-$march}
flags="$opts -march=$march"
if [ "$($cc -dumpmachine)" = "$(cc -dumpmachine)" ]; then
  where="CPU: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')"
else
  where="target: $($cc -dumpmachine) (compiled only, not run)"
fi
echo "Compiler: $($cc --version | head -1); flags: \`$flags\`; $where."
echo
for f in $files; do
  echo "\`$f\`:"
  echo
  echo '```'
  vectorized "$cc" "$march" "$f" |
    while IFS=: read -r file line rest; do
      echo "$file:$line:$rest   [in $(function_of "$file" "$line")]"
    done
  echo '```'
  echo
done
