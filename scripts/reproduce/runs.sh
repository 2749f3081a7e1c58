# runs.sh — sourced by the study modules of `make reproduce` that run one
# scene several times (scripts/reproduce/walker.sh, swimmer.sh).
#
# Design.  A module lists its runs as `run NAME SIM ARGS...`; each writes
# OUTDIR/NAME.h5 and, when the simulator exits 0, OUTDIR/NAME.done holding
# the command line.  A run whose .done matches the command line is complete
# and kept (the driver may hand a module the previous run's files), any
# other is made again.  At most two runs go at once (the machine's two
# cores), each under `nice -n 19`; `finish` waits for them and fails if one
# failed.  OUTDIR/commands.txt gets every command line, for meta.json.
RUNS_PIDS=""
RUNS_FAILED=0

run() {
  name=$1; shift
  line="$* --quiet --out $OUTDIR/$name.h5"
  echo "$line" >> "$OUTDIR/commands.txt"
  if [ -f "$OUTDIR/$name.done" ] && [ "$(cat "$OUTDIR/$name.done")" = "$line" ] && [ -f "$OUTDIR/$name.h5" ]; then
    echo "$name: kept (complete run of the same command)" >&2
    return 0
  fi
  rm -f "$OUTDIR/$name.done"
  set -- $RUNS_PIDS
  if [ $# -ge 2 ]; then
    wait "$1" || RUNS_FAILED=1
    shift
    RUNS_PIDS="$*"
  fi
  ( start=$(date +%s)
    if nice -n 19 $line > "$OUTDIR/$name.log" 2>&1; then
      echo "$line" > "$OUTDIR/$name.done"
      echo "$name: $(( $(date +%s) - start )) s" >&2
    else
      echo "$name: FAILED (see $OUTDIR/$name.log)" >&2
      exit 1
    fi ) &
  RUNS_PIDS="$RUNS_PIDS $!"
}

finish() {
  for p in $RUNS_PIDS; do wait "$p" || RUNS_FAILED=1; done
  RUNS_PIDS=""
  [ $RUNS_FAILED = 0 ]
}
