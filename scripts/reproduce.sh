#!/bin/sh
# reproduce.sh — `make reproduce`: every study of Zhang et al. 2019 that
# sinew reproduces, run at a budget, and docs/reproduction.md written from
# what the runs measured.
#
#   scripts/reproduce.sh [quick|full] [--out DIR] [--page FILE] [STUDY ...]
#
# Design.  Each study is a module, scripts/reproduce/STUDY.sh BUDGET OUTDIR,
# which runs its scenes into OUTDIR and leaves there meta.json and
# rows.jsonl (scripts/reproduce/rows.py: the reference's claims, sinew's
# figures from this run, verdicts).  This driver runs the modules one after
# the other (each uses the machine's cores as it sees fit), times each, and
# keeps going when one fails: its section of the page then says it failed
# and where its log is; its status file records the commit and the time it
# ran.  scripts/reproduce_page.py then writes the page from every module's
# files (a study run again alone replaces its own section only), with the
# commits, the machine and the budget.
# quick (the default) is meant to take about half an hour on two cores;
# full is the reference's settings, hours.  A module may keep runs that are
# complete from a previous call with the same budget.
set -u
ROOT=$(cd "$(dirname "$0")/.." && pwd)
cd "$ROOT" || exit 1
BUDGET=quick
OUT=
PAGE=docs/reproduction.md
STUDIES_ALL="elbow elbow_hardening assisted swimmer walker snake_continuum snake_terrain snake_muscular wing"
STUDIES=
while [ $# -gt 0 ]; do   # options and studies in any order
  case $1 in
    quick|full) BUDGET=$1; shift ;;
    --out) OUT=$2; shift 2 ;;
    --page) PAGE=$2; shift 2 ;;
    -h|--help) sed -n '2,20p' "$0"; exit 0 ;;
    -*) echo "reproduce.sh: unknown option $1" >&2; exit 2 ;;
    *) STUDIES="$STUDIES $1"; shift ;;
  esac
done
OUT=${OUT:-build/reproduce/$BUDGET}
STUDIES=${STUDIES:-$STUDIES_ALL}
for s in $STUDIES; do
  [ -x "scripts/reproduce/$s.sh" ] || [ -f "scripts/reproduce/$s.sh" ] || {
    echo "reproduce.sh: no study '$s' (scripts/reproduce/$s.sh); the studies are: $STUDIES_ALL" >&2
    exit 2
  }
done
mkdir -p "$OUT"
[ -x bin/sinewc ] || { echo "reproduce.sh: bin/sinewc is missing: run make first" >&2; exit 2; }
echo "reproduce.sh: budget $BUDGET, into $OUT: $STUDIES"
failed=0
for s in $STUDIES; do
  dir=$OUT/$s
  mkdir -p "$dir"
  rm -f "$dir/status" "$dir/rows.jsonl" "$dir/meta.json"
  echo "reproduce.sh: $s ..."
  load=$(cut -d' ' -f1 /proc/loadavg 2>/dev/null || echo 0)
  t0=$(date +%s.%N)
  sh "scripts/reproduce/$s.sh" "$BUDGET" "$dir" > "$dir/module.log" 2>&1
  rc=$?
  t1=$(date +%s.%N)
  wall=$(awk "BEGIN { printf \"%.0f\", $t1 - $t0 }")
  commit=$(git rev-parse --short=12 HEAD 2>/dev/null || echo unknown)
  # "+": the sources differ from the commit (the page and its plots, which
  # this command writes, do not count)
  case $PAGE in /*) mine= ;; *) mine=":(exclude)$PAGE" ;; esac
  [ -n "$(git status --porcelain --untracked-files=no -- . ${mine:+"$mine"} \
      ${mine:+":(exclude)$(dirname "$PAGE")/img/reproduce"} 2>/dev/null)" ] && commit="$commit+"
  printf '{"exit": %d, "wall": %s, "budget": "%s", "commit": "%s", "made": "%s", "load": %s}\n' "$rc" "$wall" \
    "$BUDGET" "$commit" "$(date -u '+%Y-%m-%d %H:%M UTC')" "$load" > "$dir/status"
  if [ $rc -ne 0 ]; then
    failed=$((failed + 1))
    echo "reproduce.sh: $s FAILED (exit $rc, $wall s; $dir/module.log):" >&2
    tail -5 "$dir/module.log" >&2
  else
    echo "reproduce.sh: $s done in $wall s"
  fi
done
/usr/bin/python3 scripts/reproduce_page.py "$OUT" --budget "$BUDGET" --page "$PAGE" --studies $STUDIES_ALL || exit 1
echo "reproduce.sh: wrote $PAGE ($failed of the studies failed)"
[ $failed -eq 0 ]
