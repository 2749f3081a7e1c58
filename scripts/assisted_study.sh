#!/bin/sh
# assisted_study.sh — `make assisted`: the injured elbow assisted by an
# artificial muscle (Zhang et al. 2019, Suppl. Note 6.2, Fig. 7), from
# examples/elbow_assisted.sinew: the healthy arm, the injured arm (half of
# each head's filaments passive), and the injured arm with the AM releasing
# its twist at three rates, 0.7 s each; then the figure and the table.
#
#   scripts/assisted_study.sh [--out DIR] [--duration T] [--dt DT] [CASE ...]
#
# CASE: healthy, injured, am_0.25, am_0.5, am_1 (the AM's filament radius
# grows by r0 times the rate each second; the reference's code calls 1/s its
# "max rate"); default all.  DIR (default build/assisted) gets CASE.h5 and
# CASE.log (the simulator's summary with its wall time), assisted.png and
# assisted.md (scripts/assisted_report.py).  A complete run is not made
# again.  About 35 s for each arm without the AM and 2 to 3 min with it, at the
# default step (the AM's, 0.33 us), on one core here; two runs at a time.
# --duration T runs each case for T only (a try; never taken for complete),
# --dt DT at another step (for the step study of docs/validation.md).
set -eu
ROOT=$(cd "$(dirname "$0")/.." && pwd)
OUT=build/assisted
DURATION=
DT=
while [ $# -gt 0 ]; do
  case $1 in
    --out) OUT=$2; shift 2 ;;
    --duration) DURATION=$2; shift 2 ;;
    --dt) DT=$2; shift 2 ;;
    -*) echo "assisted_study.sh: unknown option $1" >&2; exit 2 ;;
    *) break ;;
  esac
done
CASES=${*:-healthy injured am_0.25 am_0.5 am_1}
mkdir -p "$OUT"
export SINEW_PATH="$ROOT/models"
MODEL="$ROOT/examples/elbow_assisted.sinew"
"$ROOT/bin/sinewc" --let assisted=0 --let injured=0 "$MODEL" -o "$OUT/healthy"
"$ROOT/bin/sinewc" --let assisted=0 "$MODEL" -o "$OUT/injured"
"$ROOT/bin/sinewc" "$MODEL" -o "$OUT/am"

complete() { # complete FILE: the run wrote its last frame (t = 0.7 s)
  [ -f "$1" ] && /usr/bin/python3 -c "import h5py,sys; t=h5py.File(sys.argv[1])['/time'][:]; sys.exit(0 if t[-1] > 0.6999 else 1)" "$1" 2>/dev/null
}

run() { # run CASE
  c=$1
  if [ -z "$DURATION$DT" ] && complete "$OUT/$c.h5"; then echo "assisted_study.sh: $c is complete"; return 0; fi
  case $c in
    healthy|injured) set -- "$OUT/$c" ;;
    am_*) set -- "$OUT/am" --set "release_rate=${c#am_}/s" ;;
    *) echo "assisted_study.sh: unknown case $c" >&2; return 2 ;;
  esac
  [ -n "$DURATION" ] && set -- "$@" --duration "$DURATION"
  [ -n "$DT" ] && set -- "$@" --dt "$DT"
  echo "assisted_study.sh: $c: $*"
  "$@" --out "$OUT/$c.h5" > "$OUT/$c.log" 2>&1 || echo "assisted_study.sh: $c stopped (see $OUT/$c.log)"
}

set -- $CASES
while [ $# -gt 0 ]; do   # two at a time, on this machine's two cores
  run "$1" &
  if [ $# -gt 1 ]; then run "$2" & shift; fi
  shift
  wait
done

/usr/bin/python3 "$ROOT/scripts/assisted_report.py" "$OUT" --plot "$OUT/assisted.png" --table "$OUT/assisted.md"
