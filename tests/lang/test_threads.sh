#!/bin/sh
# test_threads.sh — --threads N gives the same bits for any N (issue 10).
# The elbow (joints, muscles, boundary conditions; position Verlet) runs on
# 1, 2 and 3 threads, and every dataset of the output, the energy diagnostic
# included, must be bitwise equal; so must the walker (rigid bodies, ground),
# the swimmer (fluid), the terrain snake (ground, terrain) and the pendulum
# on 1 and 2 threads.  Also: --threads auto (by the model's size), --info's
# threads line, and
# clear errors for bad values.
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
SC=$ROOT/bin/sinewc
TMP=$(mktemp -d "${TMPDIR:-/tmp}/sinew-threads.XXXXXX") || exit 1
trap 'rm -rf "$TMP"' EXIT INT TERM

same() { # same A.h5 B.h5 WHAT
  out=$(/usr/bin/python3 scripts/compare_h5.py "$1" "$2" 2>&1)
  [ "$out" = "bitwise" ]; ok $? "$3 (${out})"
}

"$SC" examples/elbow_flexion.sinew -o "$TMP/elbow" 2>"$TMP/err"; ok $? "sinewc builds the elbow"
diag <"$TMP/err"
for n in 1 2 3; do
  "$TMP/elbow" --quiet --threads $n --duration 3ms --every 1ms --out "$TMP/e$n.h5" >/dev/null 2>"$TMP/err"
  ok $? "elbow runs on $n thread(s)"
  diag <"$TMP/err"
done
same "$TMP/e1.h5" "$TMP/e2.h5" "elbow: 2 threads give the bits of 1"
same "$TMP/e1.h5" "$TMP/e3.h5" "elbow: 3 threads give the bits of 1"

for scene in walker flagella_swimmer snake_terrain pendulum; do
  "$SC" examples/$scene.sinew -o "$TMP/$scene" 2>"$TMP/err" || { ok 1 "sinewc builds $scene"; diag <"$TMP/err"; continue; }
  # 3000 steps at the scene's dt
  dt=$("$TMP/$scene" --info 2>/dev/null | awk '/^dt:/ {
    s = $3 == "ns" ? 1e-9 : $3 == "us" ? 1e-6 : $3 == "ms" ? 1e-3 : 1; printf "%.17g", $2 * s; exit }')
  dur=$(awk -v dt="$dt" 'BEGIN { printf "%.17g", dt * 3000 }')
  "$TMP/$scene" --quiet --threads 1 --duration "$dur" --every "$dur" --out "$TMP/${scene}1.h5" >/dev/null 2>&1
  "$TMP/$scene" --quiet --threads 2 --duration "$dur" --every "$dur" --out "$TMP/${scene}2.h5" >/dev/null 2>&1
  same "$TMP/${scene}1.h5" "$TMP/${scene}2.h5" "$scene: 2 threads give the bits of 1"
done

"$TMP/elbow" --info --threads 2 >"$TMP/info" 2>&1
grep -q "^threads: 2 (--threads" "$TMP/info"; ok $? "--info shows the thread count and where it came from"
"$TMP/elbow" --info >"$TMP/info" 2>&1
grep -q "^threads: 1 (default" "$TMP/info"; ok $? "--info: one thread by default"
"$TMP/elbow" --info --threads auto >"$TMP/info" 2>&1
grep -q "^threads: 1 (--threads auto" "$TMP/info"; ok $? "--threads auto: one thread for the elbow's 635 slots (one per 8192)"
# one rod of 13000 elements: 13001 slots, a second thread (one per 8192, rounded)
printf 'material soft { E = 1 MPa; density = 1000 kg/m^3; }\nrod r { material = soft; start = (0, 0, 0) m; direction = (1, 0, 0); normal = (0, 0, 1);\n        length = 1 m; radius = 1 mm; elements = 13000; }\nsimulate { duration = 1 ms; }\n' >"$TMP/long.sinew"
"$SC" "$TMP/long.sinew" -o "$TMP/long" 2>"$TMP/err"; ok $? "sinewc builds a rod of 13000 elements"
diag <"$TMP/err"
want=2; [ "$(nproc)" -lt 2 ] && want=1
"$TMP/long" --info --threads auto >"$TMP/info" 2>&1
grep -q "^threads: $want (--threads auto" "$TMP/info"; ok $? "--threads auto: $want threads for 13001 slots on $(nproc) processors"
for bad in 0 -1 two 1.5 1000; do
  "$TMP/elbow" --quiet --threads "$bad" --duration 1us --out "$TMP/x.h5" >/dev/null 2>"$TMP/err"
  rc=$?
  [ $rc -eq 2 ] && grep -q -- "--threads" "$TMP/err" && [ ! -e "$TMP/x.h5" ]
  ok $? "--threads $bad: exit 2 naming the option, nothing run (got $rc)"
  diag <"$TMP/err"
done
done_testing
