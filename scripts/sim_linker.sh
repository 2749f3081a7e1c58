#!/bin/sh
# sim_linker.sh — the linker flag sinewc passes when it builds a simulator,
# and `make` when it links sinew's own programs: -fuse-ld=gold where the C
# compiler links a program with it, else nothing (the compiler's default
# linker, GNU ld).
#
# Why: a simulator links the runtime's archive and HDF5's static one
# (hdf5_link.sh), and GNU ld takes twice as long over them as gold, which
# binutils installs beside it: 0.40 s against 0.21 s for the frog leg of
# tests/scenes (medians of 3, AMD EPYC), of about 0.6 s for the whole
# `sinewc model -o sim`.  Same code, same results (h5diff of the two
# simulators' output: no difference).  The Makefile runs this once per
# make (LD_FAST); sinewc.c has the flag baked in.
# Usage: sh scripts/sim_linker.sh [CC]
cc=${1:-${CC:-cc}}
dir=$(mktemp -d 2>/dev/null) || exit 0
printf 'int main(void) { return 0; }\n' >"$dir/probe.c"
# a real output file: some linkers replace their output, and /dev/null is not ours
if "$cc" -fuse-ld=gold "$dir/probe.c" -o "$dir/probe" >/dev/null 2>&1 && "$dir/probe"; then
  echo "-fuse-ld=gold"
fi
rm -rf "$dir"
