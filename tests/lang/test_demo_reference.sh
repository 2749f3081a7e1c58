#!/bin/sh
# test_demo_reference.sh — the 50 ns reference `make demo` draws beside its
# run, stored because it takes ~5 min (examples/reference/elbow_flexion_50ns.csv),
# is well-formed and is still the scene's:
#   - the file: provenance lines (command, revision, date, model, dt 5e-08 s,
#     integrator position-verlet), the header time_s,angle_rad,force_N, 501 frames
#     1 ms apart from 0 to 0.5 s, finite numbers, the forearm horizontal at
#     t = 0 (angle -90 deg) with the muscle slack (force 0), and an elbow
#     that flexes (the angle's range over 60 deg, the force's over 40 N);
#   - the scene compiled now and run as the reference was (its own
#     integrator, position Verlet, at 50 ns) for the first 5 ms reproduces
#     the stored frames to 1e-6 of their ranges: the same arithmetic, so a
#     change of the scene, the model or the runtime shows here first;
#   - compiled and run as `make demo` runs it (the Makefile's DEMO_LETS and
#     DEMO_RUN: bones and tendons implicit, 125 us) for 200 ms, the biceps'
#     build-up and the start of the swing, it is within 1% of the ranges and
#     its angle within 0.2%, and the same run with 1% more strength is not
#     (its angle is off by 0.6%: the run sees the muscle);
#   - bones and tendons implicit, all 79 joints and the 36 filaments'
#     damping are in the joints' system (--info), and at 100 and 50 us the
#     first 200 ms are within 1%, closer at 50 us;
#   - scripts/demo_elbow.py compare on that run prints the summary line and
#     writes a PNG, exits 5 under --within below its difference, and a
#     malformed reference is one line and exit 4, never a traceback.
# When the scene or the model changes on purpose, `make demo-reference`
# stores a new reference (~5 min).  About 12 s of one core.
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
scratch demo-ref
SC=$ROOT/bin/sinewc   # the optimised build: the runs are 125000 steps
PY=/usr/bin/python3
DEMO=scripts/demo_elbow.py
REF=$(sed -n 's/^DEMO_REF = //p' Makefile)
RUN=$(sed -n 's/^DEMO_RUN = //p' Makefile)
MODEL=$(sed -n 's/^DEMO_MODEL = //p' Makefile)
LETS=$(sed -n 's/^DEMO_LETS = //p' Makefile)

[ -n "$REF" ] && [ -n "$RUN" ] && [ "$MODEL" = examples/elbow_flexion.sinew ]
ok $? "the Makefile names the demo's scene, run and reference ($MODEL; $RUN; $REF)"

# ---- the stored file, read line by line (not by demo_elbow.py)
$PY - "$REF" >"$TMP/form" 2>&1 <<'EOF'
import math, sys
path = sys.argv[1]
meta, rows, header, bad = {}, [], None, []
for no, line in enumerate(open(path, encoding="utf-8"), 1):
    line = line.rstrip("\n")
    if line.startswith("#"):
        k, sep, v = line[1:].partition(":")
        if sep:
            meta[k.strip()] = v.strip()
    elif header is None:
        header = line
    else:
        try:
            r = [float(x) for x in line.split(",")]
            if len(r) != 3 or not all(math.isfinite(x) for x in r):
                raise ValueError
            rows.append(r)
        except ValueError:
            bad.append(f"line {no}: {line!r}")
for k in ("command", "revision", "date", "model_sha256", "dt", "integrator"):
    if not meta.get(k):
        bad.append(f"no '# {k}: ...' line")
if meta.get("dt") != "5e-08 s" or meta.get("integrator") != "position-verlet":
    bad.append(f"dt {meta.get('dt')!r} and integrator {meta.get('integrator')!r}, "
               "not '5e-08 s' and 'position-verlet'")
if header != "time_s,angle_rad,force_N":
    bad.append(f"header {header!r}")
if len(rows) != 501:
    bad.append(f"{len(rows)} frames, not 501")
elif any(abs(r[0] - i * 1e-3) > 1e-9 for i, r in enumerate(rows)):
    bad.append("the frames are not 1 ms apart from 0 to 0.5 s")
else:
    a = [r[1] for r in rows]
    f = [r[2] for r in rows]
    if abs(a[0] + math.pi / 2) > 1e-9 or f[0] != 0:
        bad.append(f"at t = 0: angle {a[0]} rad, force {f[0]} N (expected -pi/2 and 0)")
    if math.degrees(max(a) - min(a)) < 60 or max(f) - min(f) < 40:
        bad.append(f"ranges {math.degrees(max(a) - min(a)):.3g} deg, {max(f) - min(f):.3g} N")
    print(f"{len(rows)} frames; angle range {math.degrees(max(a) - min(a)):.4g} deg, "
          f"force range {max(f) - min(f):.4g} N; {meta.get('command')}, "
          f"git {meta.get('revision')}, {meta.get('date')}")
for b in bad:
    print(b)
sys.exit(1 if bad else 0)
EOF
ok $? "$REF is well-formed: provenance, header, 501 frames 1 ms apart, -90 deg and 0 N at t = 0"
diag <"$TMP/form"

# ---- short runs of the scene as it is now
"$SC" "$MODEL" -o "$TMP/sim" >"$TMP/log" 2>&1
ok $? "$MODEL compiles"
diag <"$TMP/log"
# shellcheck disable=SC2086  # DEMO_LETS is a list of options
"$SC" "$MODEL" $LETS -o "$TMP/demo_sim" >"$TMP/log" 2>&1
ok $? "$MODEL compiles as make demo compiles it ($LETS)"
diag <"$TMP/log"

# agree RUN.h5 UNTIL TOL [angle]: the run's frames up to UNTIL (s) against
# the stored ones at the same times, the largest difference of each curve
# relative to its range in the reference; exit 0 when both (or, with
# `angle`, the angle's) are within TOL
agree() {
  $PY - "$REF" "$@" <<'EOF'
import sys
import h5py
import numpy as np
ref, run, until, tol = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4])
only_angle = len(sys.argv) > 5 and sys.argv[5] == "angle"
d = np.array([[float(x) for x in l.split(",")] for l in open(ref)
              if l[:1].isdigit() or l[:1] == "-"])
with h5py.File(run, "r") as f:
    t = f["time"][()]
    a = f["joints/arm.elbow/angle"][()]
    fo = f["muscles/arm.biceps_long/force"][()]
n = int(round(until / 1e-3)) + 1
if len(t) < n or np.max(np.abs(t[:n] - d[:n, 0])) > 1e-9:
    print(f"{run}: {len(t)} frames, not at the reference's times 0 to {until} s")
    sys.exit(1)
ea = np.max(np.abs(a[:n] - d[:n, 1])) / np.ptp(d[:, 1])
ef = np.max(np.abs(fo[:n] - d[:n, 2])) / np.ptp(d[:, 2])
print(f"over 0 to {until * 1e3:g} ms: angle {ea:.3g}, force {ef:.3g} of their ranges "
      f"(tolerance {tol:g})")
sys.exit(0 if (ea if only_angle else max(ea, ef)) <= tol else 1)
EOF
}

"$TMP/sim" --quiet --dt 50ns --duration 5ms --out "$TMP/fine.h5" >"$TMP/log" 2>&1 &&
  agree "$TMP/fine.h5" 0.005 1e-6 >"$TMP/agree" 2>&1
ok $? "as the reference ran (Verlet, 50 ns), the first 5 ms reproduce the stored frames"
cat "$TMP/log" "$TMP/agree" | diag

# shellcheck disable=SC2086  # DEMO_RUN is a list of options
"$TMP/demo_sim" --quiet $RUN --duration 200ms --out "$TMP/demo.h5" >"$TMP/log" 2>&1 &&
  agree "$TMP/demo.h5" 0.2 0.01 >"$TMP/agree" 2>&1 &&
  agree "$TMP/demo.h5" 0.2 0.002 angle >>"$TMP/agree" 2>&1
ok $? "as make demo runs it ($RUN), the first 200 ms are within 1% of the stored curves, the angle within 0.2%"
cat "$TMP/log" "$TMP/agree" | diag

# shellcheck disable=SC2086
"$TMP/demo_sim" --quiet $RUN --duration 200ms --set strength=0.0808 --out "$TMP/strong.h5" \
  >"$TMP/log" 2>&1
agree "$TMP/strong.h5" 0.2 0.002 angle >"$TMP/agree" 2>&1
[ $? -eq 1 ] && grep -q '^over' "$TMP/agree"
ok $? "with 1% more strength, the angle is not (the run sees the muscle)"
cat "$TMP/log" "$TMP/agree" | diag

# ---- the demo's report
$DEMO compare "$TMP/demo.h5" "$REF" -o "$TMP/demo.png" --wall 1.5 --within 1 >"$TMP/out" 2>&1
rc=$?
last=$(tail -n 1 "$TMP/out")
[ $rc -eq 0 ] && [ "$(head -c 4 "$TMP/demo.png" | od -An -c | tr -d ' ')" = '211PNG' ] &&
  echo "$last" | grep -Eq '^simulated 0\.2 s in 1\.5 s wall, within [0-9.e-]+% \(angle\) and [0-9.e-]+% \(force\) of the 50 ns reference, at dt = 125 us \([0-9.e+]+ x the reference.s step, imex\)$'
ok $? "demo_elbow.py compare: a PNG and the summary line"
diag <"$TMP/out"

$DEMO compare "$TMP/strong.h5" "$REF" --within 0.01 >"$TMP/out" 2>&1
rc=$?
[ $rc -eq 5 ] && tail -n 1 "$TMP/out" | grep -q '^demo_elbow: the run is NOT within 0.01% of the reference' &&
  ! grep -q Traceback "$TMP/out"
ok $? "demo_elbow.py compare --within: exit 5 and one line beyond it"
diag <"$TMP/out"

sed '20s/.*/0.019,oops,1/' "$REF" >"$TMP/bad.csv"
$DEMO compare "$TMP/demo.h5" "$TMP/bad.csv" >"$TMP/out" 2>&1
rc=$?
[ $rc -eq 4 ] && [ "$(wc -l <"$TMP/out")" -eq 1 ] &&
  grep -q "^demo_elbow: $TMP/bad.csv:20: expected three numbers, got '0.019,oops,1'$" "$TMP/out"
ok $? "a malformed reference: exit 4, one line naming the file and line"
diag <"$TMP/out"
# ---- every bone and tendon implicit, with every joint and the filaments'
# Hill damping in the joints' system (docs/physics.md, "Joints on implicit
# rods"): the same scene at 100 us, 2000 times the reference's step, stays
# within 1% of its curves over the first 200 ms (the biceps' build-up and
# the start of the swing), and at 50 us it is closer.
"$SC" "$MODEL" --let implicit_bones=true --let implicit_tendons=true -o "$TMP/imp" >"$TMP/log" 2>&1 &&
  "$TMP/imp" --info --integrator imex >"$TMP/info" 2>&1 &&
  grep -q "79 of 79 joints.*7 implicit rods through 15 nodes, 72 rod nodes, the Hill damping of 36 filaments" "$TMP/info"
ok $? "implicit bones and tendons: all 79 joints and 36 filaments' damping in the system (--info)"
grep -q "note: the estimate leaves out the loads' own stiffness on implicit rods" "$TMP/info"
ok $? "--info says the estimate does not hold for it"
grep "joints, those" "$TMP/info" | diag
"$TMP/imp" --quiet --integrator imex --dt 100us --duration 200ms --out "$TMP/imp100.h5" >"$TMP/log" 2>&1 &&
  agree "$TMP/imp100.h5" 0.2 0.01 >"$TMP/agree100" 2>&1
ok $? "implicit bones and tendons at 100 us: the first 200 ms within 1% of the stored curves"
cat "$TMP/log" "$TMP/agree100" | diag
"$TMP/imp" --quiet --integrator imex --dt 50us --duration 200ms --out "$TMP/imp50.h5" >"$TMP/log" 2>&1 &&
  agree "$TMP/imp50.h5" 0.2 0.01 >"$TMP/agree50" 2>&1
ok $? "and at 50 us as well"
cat "$TMP/log" "$TMP/agree50" | diag
$PY - "$TMP/agree100" "$TMP/agree50" >"$TMP/ratio" 2>&1 <<'EOF'
import re, sys
e = [max([float(x) for x in re.findall(r"(?:angle|force) ([0-9.e+-]+)", open(p).read())] or [1e9])
     for p in sys.argv[1:]]
print(f"largest relative difference at 100 us {e[0]:.3g}, at 50 us {e[1]:.3g}: ratio {e[0] / e[1]:.3g}")
sys.exit(0 if e[1] < 0.75 * e[0] else 1)
EOF
ok $? "halving the step to 50 us shrinks the difference (by at least a quarter)"
diag <"$TMP/ratio"
done_testing
