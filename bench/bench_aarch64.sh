#!/bin/sh
# bench_aarch64.sh [REPORT.md] — sinew on 64-bit Arm: the whole runtime and
# compiler built by Debian's cross compiler, and the rod step and the
# runtime's fast unit tests run under user-mode emulation (qemu-aarch64), for
# NEON (-march=armv8-a, every 64-bit Arm) and SVE (-march=armv8.2-a+sve, run
# at vector lengths of 128, 512 and 2048 bits).
#
# What it answers: does every file compile for Arm (GCC 12.2 for aarch64
# once stopped with an internal compiler error on three of them: vec.h,
# sw_max), do the vector loops compute there what they compute on x86
# (bench_rod --tip: the cantilever's tip after N steps, printed to 17
# digits, against the x86-64 build of `make`, its v3 and v4 builds and the
# portable library), and
# do the tests' closed-form checks hold there.  Emulation says nothing of
# speed, and none is given.  Written as the section "64-bit Arm: built and
# run under emulation" of REPORT.md (docs/benchmarks.md), which `make bench`
# runs (~5 min; ~2 more the first time, for the packages).
#
# Packages: the cross compiler, qemu-user, and the Arm builds of the
# libraries the runtime links (GSL, HDF5, cmocka: their runtime packages
# only, which sit beside the x86-64 ones; the headers are the x86-64
# -dev packages', the same on both 64-bit little-endian Linux targets; the
# Arm -dev packages would replace the x86-64 ones).  That needs dpkg to
# know the arm64 architecture, which this script adds when it is missing.
# SW_BENCH_ARM_TESTS: the runtime tests run (default: those of a quarter of
# a second or less natively, emulation being about 100 times slower, and
# none with threads: under qemu-aarch64 7.2 here a program that starts a
# pthread and joins it never returns, so test_cli's 2-thread run spins).
set -eu
out=${1:-docs/benchmarks.md}
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
title="64-bit Arm: built and run under emulation"
TESTS=${SW_BENCH_ARM_TESTS:-"test_vec test_units test_law test_model test_statics test_stability test_ground \
  test_fluid test_shape test_probe test_kinematic test_rigidity test_joint_order test_via_implicit \
  test_obstacle_roll test_signal_range test_signal_bspline test_rng test_rigid_joint test_boundary"}
SIZES="50 100 200"
cross=aarch64-linux-gnu-gcc
lib=/usr/lib/aarch64-linux-gnu
SUDO=""
[ "$(id -u)" = 0 ] || SUDO=sudo
not_run() { # the section when the packages cannot be had (no network, no root): make bench goes on
  python3 scripts/put_section.py "$out" "$title" "Not run on $(date -u '+%Y-%m-%d'): $1."
  echo "bench_aarch64: not run: $1" >&2
  exit 0
}
dpkg --print-foreign-architectures | grep -qx arm64 || {
  echo "bench_aarch64: adding the arm64 architecture to dpkg" >&2
  $SUDO dpkg --add-architecture arm64 || not_run "dpkg could not add the arm64 architecture"
}
sh scripts/deps.sh gcc-aarch64-linux-gnu:/usr/bin/$cross libc6-dev-arm64-cross:/usr/aarch64-linux-gnu/include/stdio.h \
  qemu-user:/usr/bin/qemu-aarch64 libgsl27:arm64:$lib/libgsl.so.27 libgslcblas0:arm64:$lib/libgslcblas.so.0 \
  libhdf5-103-1:arm64:$lib/libhdf5_serial.so.103 libcmocka0:arm64:$lib/libcmocka.so.0 ||
  not_run "the cross compiler, qemu-user or the Arm libraries could not be installed"
make --no-print-directory bin/sinewc build/bench/bench_rod build/bench/bench_rod_v3 build/bench/bench_rod_v4 \
  build/libsinewrt-portable.a >/dev/null
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# bench_rod on the portable library (sinewc --portable: any x86-64)
${CC:-cc} -std=c11 -D_DEFAULT_SOURCE -O3 -march=x86-64 -fno-math-errno -fopenmp -Iruntime/include bench/bench_rod.c \
  -o "$tmp/bench_rod_portable" build/libsinewrt-portable.a $(pkg-config --libs hdf5 gsl) -lm
warn="-Wall -Wextra -Wshadow -Wstrict-prototypes -Wmissing-prototypes"
opts="-std=c11 -D_DEFAULT_SOURCE -O3 -fno-math-errno -fopenmp -g0"
inc="-Iruntime/include -Iruntime -Iruntime/engine -Iruntime/io -Iruntime/study -Itests/runtime $(pkg-config --cflags hdf5 gsl)"
libs="-L$lib -l:libhdf5_serial.so.103 -l:libgsl.so.27 -l:libgslcblas.so.0 -l:libcmocka.so.0 -lm"
# every file of the runtime (but the MPI transport, which needs an MPI
# build for Arm) and of the compiler, at make's flags: what does not build
for m in armv8-a armv8.2-a+sve; do
  d=$tmp/$m
  mkdir -p "$d/o"
  : > "$d/failed"
  n=0
  for f in runtime/*/*.c compiler/*.c build/lang/sinew.tab.c; do
    case $f in *study_mpi.c) continue ;; esac
    n=$((n + 1))
    o=$d/o/$(echo "$f" | tr / _ | sed 's/\.c$/.o/')
    if ! $cross $opts $warn -march=$m $inc -Icompiler -Ibuild/lang -Ilang -c "$f" -o "$o" > "$d/log" 2>&1 ||
       grep -q 'warning:' "$d/log"; then
      echo "$f: $(grep -m1 -E 'error|warning' "$d/log")" >> "$d/failed"
    fi
  done
  echo "$n" > "$d/count"
  ar rcs "$d/libsinewrt.a" "$d"/o/runtime_*.o 2>/dev/null
  $cross $opts -march=$m $inc -DSW_BENCH_CFLAGS="\"$opts -march=$m\"" bench/bench_rod.c -o "$d/bench_rod" "$d/libsinewrt.a" $libs
  for t in $TESTS; do
    $cross $opts -march=$m $inc tests/runtime/$t.c -o "$d/$t" "$d/libsinewrt.a" $libs
  done
done
echo "bench_aarch64: built; running under qemu-aarch64" >&2
# the cantilever's tip, x86-64 and Arm
tips() { # tips LABEL CMD...: "LABEL n clamp-tip held-tip" a size
  label=$1
  shift
  for n in $SIZES; do
    echo "$label $n $("$@" --tip "$n" 3000 | awk '$1 == "clamp" || $1 == "pyelastica" { printf "%s,%s ", $4, $6 }')"
  done
}
{
  tips "x86-64 (make: -march=native)" build/bench/bench_rod
  level() { build/bench/bench_rod --cpu | awk -v k="$1" '$1 == k { print $2 }'; }
  [ "$(level x86-64-v3)" = yes ] && tips "x86-64-v3" build/bench/bench_rod_v3
  [ "$(level x86-64-v4)" = yes ] && tips "x86-64-v4" build/bench/bench_rod_v4 # a CPU without AVX-512: no row
  tips "x86-64 (portable: sinewc --portable)" "$tmp/bench_rod_portable"
  tips "armv8-a (NEON)" qemu-aarch64 -cpu max -E LD_LIBRARY_PATH=/usr/aarch64-linux-gnu/lib "$tmp/armv8-a/bench_rod"
  for vl in 16:128 64:512 256:2048; do
    tips "armv8.2-a+sve, ${vl#*:}-bit vectors" qemu-aarch64 -cpu "max,sve-default-vector-length=${vl%:*}" \
      -E LD_LIBRARY_PATH=/usr/aarch64-linux-gnu/lib "$tmp/armv8.2-a+sve/bench_rod"
  done
} > "$tmp/tips"
# the tests, two at a time
for m in armv8-a armv8.2-a+sve; do
  for t in $TESTS; do echo "$m $t"; done
done | xargs -P 2 -L 1 sh -c '
  log='"$tmp"'/$0/$1.log
  qemu-aarch64 -cpu max -E LD_LIBRARY_PATH=/usr/aarch64-linux-gnu/lib '"$tmp"'/$0/$1 > "$log" 2>&1
  echo $? >> "$log"' || true
section=$tmp/section
{
  echo "Written by bench/bench_aarch64.sh, which \`make bench\` runs. Every file of"
  echo "the runtime (but the MPI transport) and of the compiler compiled for 64-bit"
  echo "Arm by $($cross --version | head -1), at the flags of"
  echo "\`make\` with \`-march=armv8-a\` (NEON) and \`-march=armv8.2-a+sve\` (SVE) and"
  echo "its warnings; bench_rod and the fast runtime tests linked against that"
  echo "runtime and run under $(qemu-aarch64 --version | head -1) (user-mode"
  echo "emulation, \`-cpu max\`; SVE at the vector lengths shown). Emulation gives"
  echo "no speed, so no times are given."
  echo
  echo "- Host: $(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -1) (cpu family $(awk -F': *' '/^cpu family/ { print $2; exit }' /proc/cpuinfo))."
  echo "- Date: $(date -u '+%Y-%m-%d %H:%M UTC'); code: git $(git rev-parse --short HEAD)$(git diff --quiet HEAD -- runtime compiler bench || echo ' (modified)')."
  echo
  echo "**Compiled:**"
  echo
  echo "| target | files | built without warnings | not |"
  echo "|---|--:|--:|---|"
  for m in armv8-a armv8.2-a+sve; do
    d=$tmp/$m
    bad=$(wc -l < "$d/failed")
    echo "| \`-march=$m\` | $(cat "$d/count") | $(($(cat "$d/count") - bad)) | $(if [ "$bad" -eq 0 ]; then echo none; else sed 's/|/\\|/g' "$d/failed" | tr '\n' ';'; fi) |"
  done
  echo
  echo "**The cantilever's tip** (bench_rod --tip N 3000: 3000 Verlet steps at"
  echo "bench_rod's dt, x and z of the free end in m, clamped / held as PyElastica"
  echo "holds it), every digit a double holds:"
  echo
  echo "| build | n | tip (clamp) | tip (held) | same bits as x86-64 (make) |"
  echo "|---|--:|---|---|:-:|"
  awk '{ n = $(NF - 2); c = $(NF - 1); h = $NF; label = $0; sub(/ +$/, "", label); sub(/ [^ ]+ [^ ]+ [^ ]+$/, "", label)
         if (!(n in ref)) ref[n] = c " " h
         printf "| %s | %s | %s | %s | %s |\n", label, n, c, h, (c " " h == ref[n]) ? "yes" : "**no**" }' "$tmp/tips"
  echo
  echo "**The runtime's tests** (cmocka; each asserts against a closed form, a"
  echo "convergence order or an invariant, tests/runtime):"
  echo
  echo "| test | armv8-a (NEON) | armv8.2-a+sve (512-bit vectors) |"
  echo "|---|---|---|"
  for t in $TESTS; do
    row="| $t"
    for m in armv8-a armv8.2-a+sve; do
      log=$tmp/$m/$t.log
      pass=$(sed -n 's/^\[  PASSED  \] \([0-9]*\) test.*/\1/p' "$log" | tail -1)
      fail=$(sed -n 's/^\[  FAILED  \] \([0-9]*\) test.*/\1/p' "$log" | tail -1)
      rc=$(tail -n 1 "$log")
      if [ "$rc" = 0 ] && [ -z "$fail" ]; then row="$row | ${pass:-?} passed"
      else row="$row | **${fail:-?} failed** (exit $rc)"; fi
    done
    echo "$row |"
  done
} > "$section"
python3 scripts/put_section.py "$out" "$title" "$(cat "$section")"
cat "$section"
