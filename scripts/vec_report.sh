#!/bin/sh
# vec_report.sh [MARCH] — what GCC's vectorizer did with the hot loops of the
# step (rod.c, integrate.c, loads.c, muscle.c, stability.c) at the flags of
# `make`, for -march=MARCH (native unless given; x86-64-v3 and x86-64-v4 are
# the levels `make bench` compares): each loop of those files that it
# vectorized, with the vector width, as -fopt-info-vec-optimized reports it.
# Printed as Markdown for docs/performance.md ("What the vectorizer did").
set -eu
cc=${CC:-cc}
flags="-std=c11 -D_DEFAULT_SOURCE -O3 -march=${1:-native} -fno-math-errno -fopenmp"
echo "Compiler: $($cc --version | head -1); flags: \`$flags\`; CPU: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')."
echo
for f in runtime/engine/rod.c runtime/engine/integrate.c runtime/engine/loads.c runtime/engine/muscle.c runtime/engine/stability.c; do
  echo "\`$f\`:"
  echo
  echo '```'
  # each report line, with the function its loop is in (for a loop whose
  # first statement was inlined from vec.h, the report names vec.h)
  $cc $flags -Iruntime/include -Iruntime -fopt-info-vec-optimized -c "$f" -o /dev/null 2>&1 |
    grep 'loop vectorized' | sed 's|^runtime/||' | sort -t: -k1,1 -k2,2n -u |
    while IFS=: read -r file line rest; do
      fn=$(awk -v n="$line" 'NR <= n && /^[a-z].*[a-z_0-9]+\((const|int|double|void|sw)/ { f = $0 }
        END { match(f, /[a-z_0-9]+\((const|int|double|void|sw)/); f = substr(f, RSTART, RLENGTH);
              sub(/\(.*/, "", f); print f }' "runtime/$file")
      echo "$file:$line:$rest   [in $fn]"
    done
  echo '```'
  echo
done
