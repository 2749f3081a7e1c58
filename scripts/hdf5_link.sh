#!/bin/sh
# hdf5_link.sh — the linker flags that put HDF5 into the simulators sinewc
# builds: its static archive where one links (with the libraries Debian's
# HDF5 is built against: libsz from libaec and zlib, both dependencies of
# libhdf5-dev), else pkg-config's shared library.
#
# Why static: the shared libhdf5 brings in libcurl (for its S3 driver, which
# sinew never uses) and with it TLS, Kerberos and LDAP, about 35 shared
# libraries whose loading and relocation cost every simulator 25-30 ms of
# start-up (the arm's demo, 0.10 s with the archive against 0.13 s, medians
# of 10, AMD EPYC); the archive lends only the objects a simulator calls.
# The Makefile runs this when it builds sinewc.c; the flags are baked in.
# Usage: sh scripts/hdf5_link.sh [CC]
cc=${1:-${CC:-cc}}
shared=$(pkg-config --libs hdf5 2>/dev/null)
# the archive beside the shared library pkg-config names (Debian's
# hdf5.pc has no libdir variable, only -L)
archive=""
for dir in $(pkg-config --libs-only-L hdf5 2>/dev/null | sed 's/-L//g'); do
  [ -f "$dir/libhdf5.a" ] && { archive="$dir/libhdf5.a"; break; }
done
static="$archive -lsz -lz -ldl -lm"
if [ -n "$archive" ]; then
  dir=$(mktemp -d 2>/dev/null) || { echo "$shared"; exit 0; }
  cat >"$dir/probe.c" <<'PROBE'
#include <hdf5.h>
int main(void) {
  hid_t f = H5Fcreate("probe.h5", H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  return f < 0 || H5Fclose(f) < 0;
}
PROBE
  if $cc $(pkg-config --cflags hdf5) "$dir/probe.c" -o "$dir/probe" $static >/dev/null 2>&1; then
    rm -rf "$dir"
    echo "$static"
    exit 0
  fi
  rm -rf "$dir"
fi
echo "$shared"
