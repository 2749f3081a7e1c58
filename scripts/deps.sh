#!/bin/sh
# deps.sh — install the Debian packages sinew needs, only those that are missing.
# Called by `make test`, `make demo`, `make bench` and `make plots` so that each works on a
# fresh Debian machine.  docs/dependencies.md says why each package is here.
# With arguments (PKG:PROBE ..., PKG may be PKG:ARCH), installs those instead: the heavy packages that only one
# test or tool needs (ParaView, ffmpeg) are pulled in by that test or tool (test_paraview.sh,
# test_movie.sh, `sinew-plot movie`), not by every build.
set -e
# package:probe-file pairs; a package is missing when its probe file is absent.
PKGS="
flex:/usr/bin/flex
bison:/usr/bin/bison
libhdf5-dev:/usr/include/hdf5/serial/hdf5.h
hdf5-tools:/usr/bin/h5dump
libgsl-dev:/usr/include/gsl/gsl_math.h
pkg-config:/usr/bin/pkg-config
libcmocka-dev:/usr/include/cmocka.h
perl:/usr/bin/prove
python3-h5py:/usr/lib/python3/dist-packages/h5py/__init__.py
python3-matplotlib:/usr/lib/python3/dist-packages/matplotlib/__init__.py
openmpi-bin:/usr/bin/mpirun
libopenmpi-dev:/usr/lib/x86_64-linux-gnu/openmpi/include/mpi.h
"
[ $# -gt 0 ] && PKGS="$*"
missing_now() {
  missing=""
  for pair in $PKGS; do
    pkg=${pair%:*}; probe=${pair##*:} # at the last colon: a package may be PKG:ARCH
    [ -e "$probe" ] || missing="$missing $pkg"
  done
}
missing_now
[ -z "$missing" ] && exit 0
# One install at a time from this script (make test runs three test files
# at once); what another call installed meanwhile is not installed again.
# The lock is at a fixed path, the same whatever TMPDIR a caller sets.
exec 9>/tmp/sinew-deps.lock
flock 9
missing_now
[ -z "$missing" ] && exit 0
echo "deps: installing$missing" >&2
SUDO=""
[ "$(id -u)" = 0 ] || SUDO=sudo
export DEBIAN_FRONTEND=noninteractive
# Another apt-get on the machine (not this script's) may hold dpkg's lock:
# each apt-get waits up to ten minutes for it (DPkg::Lock::Timeout).  A
# failed update or download is tried once more, after a fresh index.  apt's
# own messages stay on stderr, for the caller's log.  (A CI run:
# test_paraview.sh could not install python3-paraview while test_movie.sh,
# run beside it, may have been installing ffmpeg; apt's reason was not kept.)
APT="$SUDO apt-get -qq -o DPkg::Lock::Timeout=600"
apt_install() {
  $APT update >/dev/null && $APT install -y --no-install-recommends $missing >/dev/null
}
apt_install || { echo "deps: apt-get failed; trying once more" >&2; sleep 5; apt_install; }
