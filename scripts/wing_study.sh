#!/bin/sh
# wing_study.sh — the feathered wing's full runs (Zhang et al. 2019, Suppl.
# Notes 5 and 6.7, Fig. 13): models/pigeon_wing.sinew over its 0.51 s, the
# original and Fig. 13's variants, two at a time (this machine's 2 cores),
# then the angles, the stroke's frames and the variants' table and plot.
#
#   scripts/wing_study.sh [--out DIR] [--duration T] [VARIANT ...]
#
# VARIANT: original, hard (twist and shear x10 on every rod: Fig. 13 (b)),
# hard_but_barbs (x10 on bones, rachises and muscles), soft (shear and twist
# /5 on the muscles: (c)), soft_twist (twist /5 on the muscles: (d)),
# control (muscle twist x0.99: what a change of 1% moves);
# default all of these but control; and resolved (models/pigeon_wing_resolved.sinew:
# every barb and rachis on an ordinary joint, about 26 min of an idle
# core), which only runs when named, and with the original gives
# resolved.png and resolved.txt (scripts/wing_resolved_compare.py);
# resolved_hard, resolved_soft and resolved_soft_twist, (b), (c) and (d)
# on the resolved wing, and resolved_hard25, _hard50 and _hard100 (Note
# 6.7's further factors, at 0.9 of their estimates: about 240, 170 and
# 120 ns, 1.5 to 4 h each), compared with resolved in resolved_fig13.md and
# resolved_fig13.png; resolved_ib, resolved_ib_hard, _hard25, _hard50 and
# _hard100: the same with implicit barbs (sinewc --let implicit_barbs=true,
# docs/physics.md "Rod leaves"), every one at 0.9 of the estimate the
# hand's joints set, 3.38 us (about 33 min each on a quiet core, 42-48 beside
# another run), in resolved_ib_fig13.md and resolved_ib_fig13.png.
# DIR (default build/wing) gets VARIANT.h5, VARIANT.log (the
# simulator's summary, its wall time), angles.png, frames.png, fig13.png and
# fig13.md.  A run whose file is complete, or that stopped unstable, is not
# made again (delete its .h5 to redo it).  The model's
# step, 1 us, is above the hardened variants' stable estimates (418 ns for
# (b)): the kinematic ones run at half of theirs, as the simulator chooses
# when a model sets no step, and stop early (docs/validation.md); the
# resolved one at 0.9 of its own (about 80 min).  About 6 min of an idle
# core per kinematic run at 1 us (7 with the other logical CPU busy), 26
# for a resolved one (30).  --serial runs the variants one after another;
# two such studies started side by side (distinct variants, one DIR) keep
# both logical CPUs busy with no run waiting on its pair.
# --duration T (e.g. 2ms) runs each variant for T only, to try the script;
# such runs are never taken for complete.
set -eu
ROOT=$(cd "$(dirname "$0")/.." && pwd)
OUT=build/wing
DURATION=
SERIAL=
while [ $# -gt 0 ]; do
  case $1 in
    --out) OUT=$2; shift 2 ;;
    --duration) DURATION=$2; shift 2 ;;
    --serial) SERIAL=1; shift ;;
    -*) echo "wing_study.sh: unknown option $1" >&2; exit 2 ;;
    *) break ;;
  esac
done
VARIANTS=${*:-original soft soft_twist hard_but_barbs hard}
mkdir -p "$OUT"
export SINEW_PATH="$ROOT/models"
compile() { # compile MODEL SIM [SINEWC ARGS]: unless SIM is newer than the models and the compiler
  if [ -n "$(find "$ROOT/models" "$ROOT/bin/sinewc" -newer "$2" 2>/dev/null | head -1)" ] \
     || [ ! -f "$2" ]; then
    m=$1 sim=$2; shift 2
    "$ROOT/bin/sinewc" "$ROOT/models/$m" -o "$sim" "$@"
  fi
}
( flock 9   # two studies started side by side compile once
  compile pigeon_wing.sinew "$OUT/wing"
  case " $VARIANTS " in
    *" resolved_ib"*) compile pigeon_wing_resolved.sinew "$OUT/resolved_ib" --let implicit_barbs=true ;;
  esac
  case " $VARIANTS " in
    *" resolved "* | *" resolved_hard"* | *" resolved_soft"*) compile pigeon_wing_resolved.sinew "$OUT/resolved" ;;
  esac ) 9> "$OUT/.compiling"

hardened() { # hardened K: shear and twist xK on every rod (Fig. 13 (b) is K = 10)
  for p in wing barb muscle; do printf -- '--set %s_shear=%s --set %s_twist=%s ' "$p" "$1" "$p" "$1"; done
}

settings() {
  case $1 in
    original) echo "" ;;
    hard) hardened 10 ;;
    hard_but_barbs) echo "--set wing_shear=10 --set wing_twist=10 --set muscle_shear=10 --set muscle_twist=10" ;;
    soft | resolved_soft) echo "--set muscle_shear=0.2 --set muscle_twist=0.2" ;;
    soft_twist | resolved_soft_twist) echo "--set muscle_twist=0.2" ;;
    control) echo "--set muscle_twist=0.99" ;; # how far a change of 1% moves the run
    resolved_hard) hardened 10 ;;
    resolved_hard25) hardened 25 ;;   # the reference's further factors:
    resolved_hard50) hardened 50 ;;   # "change nothing further" (Suppl.
    resolved_hard100) hardened 100 ;; # Note 6.7)
    resolved_ib) echo "" ;;          # implicit barbs (rod leaves), at 0.9 of its estimate
    resolved_ib_hard) hardened 10 ;;
    resolved_ib_hard25) hardened 25 ;;
    resolved_ib_hard50) hardened 50 ;;
    resolved_ib_hard100) hardened 100 ;;
    resolved) echo "" ;; # its own model, at its own step (1 us)
    *) echo "wing_study.sh: unknown variant $1" >&2; exit 2 ;;
  esac
}

complete() { # complete FILE: the run wrote its last frame (t = 0.51 s)
  [ -f "$1" ] && /usr/bin/python3 -c "import h5py,sys; t=h5py.File(sys.argv[1])['/time'][:]; sys.exit(0 if t[-1] > 0.5099 else 1)" "$1" 2>/dev/null
}

step() { # step SIM FRACTION ALWAYS SETTINGS...: --dt at FRACTION of the variant's stable
         # estimate when the model's step is above it, or ALWAYS (1), shortened so that
         # whole steps span the frames' 5 ms
  sim=$1 fraction=$2 always=$3; shift 3
  "$sim" --info "$@" 2>/dev/null | awk -v q="$fraction" -v always="$always" '/^dt: / && /stable estimate/ {
    s = $0; sub(/.*stable estimate /, "", s); sub(/\).*/, "", s); split(s, e, " ")
    f = e[2] == "ns" ? 1e-9 : e[2] == "us" ? 1e-6 : e[2] == "ms" ? 1e-3 : 1
    split($0, d, " "); g = d[3] == "ns" ? 1e-9 : d[3] == "us" ? 1e-6 : d[3] == "ms" ? 1e-3 : 1
    if (always == 1) { n = int(5e-3 / (e[1] * f * q)) + 1; printf "--dt %.10gns\n", 5e6 / n }
    else if (d[2] * g > e[1] * f) printf "--dt %.6gns\n", e[1] * f * q * 1e9 }'
}

stopped() { # stopped VARIANT: its run went unstable and stopped (the hardened kinematic wings
           # do, at the same step each time: run again, they would stop again)
  [ -f "$OUT/$1.h5" ] && [ -f "$OUT/$1.log" ] && grep -q "became unstable" "$OUT/$1.log"
}

run() { # run VARIANT
  if [ -z "$DURATION" ] && complete "$OUT/$1.h5"; then echo "wing_study.sh: $1 is complete"; return 0; fi
  if [ -z "$DURATION" ] && stopped "$1"; then echo "wing_study.sh: $1 stopped before (see $OUT/$1.log)"; return 0; fi
  set -- "$1" $(settings "$1")
  v=$1; shift
  sim=$OUT/wing fraction=0.5 always=0
  # the resolved wing's hardened step: 0.9 of its estimate, which its barbs'
  # explicit bound sets (stable there over the whole stroke: validation.md);
  # with implicit barbs 0.9 of its own (the hand's joints'), above the model's 1 us
  case $v in
    resolved_ib*) sim=$OUT/resolved_ib fraction=0.9 always=1 ;;
    resolved*) sim=$OUT/resolved fraction=0.9 ;;
  esac
  set -- "$@" $(step "$sim" "$fraction" "$always" "$@")
  [ -n "$DURATION" ] && set -- "$@" --duration "$DURATION" --every 0.5ms
  echo "wing_study.sh: $v: $*"
  "$sim" --quiet "$@" --out "$OUT/$v.h5" > "$OUT/$v.log" 2>&1 || echo "wing_study.sh: $v stopped (see $OUT/$v.log)"
}

set -- $VARIANTS
if [ -n "$SERIAL" ]; then
  for v; do run "$v"; done
else
  while [ $# -gt 0 ]; do   # two at a time
    run "$1" &
    if [ $# -gt 1 ]; then run "$2" & shift; fi
    shift
    wait
  done
fi

if [ -f "$OUT/original.h5" ]; then
  /usr/bin/python3 "$ROOT/scripts/wing_angles.py" "$OUT/original.h5" --plot "$OUT/angles.png" > "$OUT/angles.txt"
  /usr/bin/python3 "$ROOT/scripts/wing_frames.py" "$OUT/original.h5" -o "$OUT/frames.png"
  set --
  for v in hard hard_but_barbs soft soft_twist control; do
    [ -f "$OUT/$v.h5" ] && set -- "$@" "$v=$OUT/$v.h5"
  done
  /usr/bin/python3 "$ROOT/scripts/wing_fig13.py" "$OUT/original.h5" "$@" --plot "$OUT/fig13.png" --table "$OUT/fig13.md"
  if [ -f "$OUT/resolved.h5" ]; then
    /usr/bin/python3 "$ROOT/scripts/wing_resolved_compare.py" "$OUT/original.h5" "$OUT/resolved.h5" \
      --plot "$OUT/resolved.png" > "$OUT/resolved.txt"
  fi
fi
if [ -f "$OUT/resolved.h5" ]; then
  set --
  for v in hard hard25 hard50 hard100 soft soft_twist; do
    [ -f "$OUT/resolved_$v.h5" ] && set -- "$@" "$v=$OUT/resolved_$v.h5"
  done
  [ $# -gt 0 ] && /usr/bin/python3 "$ROOT/scripts/wing_fig13.py" "$OUT/resolved.h5" "$@" \
    --plot "$OUT/resolved_fig13.png" --table "$OUT/resolved_fig13.md" \
    --title "The fully resolved wing hardened and softened (Suppl. Fig. 13; models/pigeon_wing_resolved.sinew)"
  set --
  for v in ib ib_hard ib_hard25 ib_hard50 ib_hard100; do
    [ -f "$OUT/resolved_$v.h5" ] && set -- "$@" "$v=$OUT/resolved_$v.h5"
  done
  [ $# -gt 0 ] && /usr/bin/python3 "$ROOT/scripts/wing_fig13.py" "$OUT/resolved.h5" "$@" \
    --plot "$OUT/resolved_ib_fig13.png" --table "$OUT/resolved_ib_fig13.md" \
    --title "Suppl. Fig. 13 (b) x10 to x100 on the resolved wing, implicit barbs (--let implicit_barbs=true)"
fi
