#!/bin/sh
# test_activation_range.sh — an activation the model drives outside [0, 1]
# is clamped by the runtime, and nothing about it is silent any more:
#   - sinewc warns at the activate line, naming the muscle and the value the
#     activation reaches, when a signal's values or a param's default take it
#     there (a plain number out of range keeps its own warning, where it is);
#   - the simulator warns once a muscle at the start of a run, so that
#     `--set strength=1.5` is told too; in range, nothing is said.
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
scratch activation
SC=$SINEWC_CHECK
cat >"$TMP/act.sinew" <<'MODEL'
param strength = 1.5;
material tissue { E = 10 kPa; density = 1060 kg/m^3; poisson = 0.5; }
material bone { E = 15 GPa; density = 1750 kg/m^3; poisson = 0.3; }
bone a { material = bone; start = (0, 0, 0) m; direction = (1, 0, 0); normal = (0, 0, 1); length = 0.2 m; radius = 5 mm; elements = 8; }
bone b { material = bone; start = (0.25, 0, 0) m; direction = (1, 0, 0); normal = (0, 0, 1); length = 0.2 m; radius = 5 mm; elements = 8; }
muscle flexor { material = tissue; from = a.at(0.5); to = b.at(0.5); filaments = 3; elements = 6; radius = 3 mm; sigma_max = 300 kPa; }
muscle extensor { material = tissue; from = a.at(0.6); to = b.at(0.4); filaments = 3; elements = 6; radius = 3 mm; sigma_max = 300 kPa; }
clamp a.start;
activate flexor = strength * ramp(0, 1, over = 0.01 s);
activate extensor = ramp(0, 3, over = 0.01 s);
simulate { duration = 0.2 ms; }
output "act.h5" every 0.1 ms;
MODEL
"$SC" "$TMP/act.sinew" -o "$TMP/act" 2>"$TMP/err"; ok $? "the model compiles"
diag <"$TMP/err"
grep -qxF "$TMP/act.sinew:9:1: warning: the activation of muscle 'flexor' reaches 1.5 with the params' defaults; it acts as 1 (activations are clamped to [0, 1])" "$TMP/err"
ok $? "sinewc warns at the activate line of a param's default that drives it to 1.5"
grep -qxF "$TMP/act.sinew:10:1: warning: the activation of muscle 'extensor' reaches 3; it acts as 1 (activations are clamped to [0, 1])" "$TMP/err"
ok $? "and of a ramp to 3"

run() { (cd "$TMP" && ./act --quiet --duration 0.1ms "$@") >/dev/null 2>"$TMP/run"; }
run; ok $? "the simulator runs"
[ "$(grep -c 'warning: muscle' "$TMP/run")" -eq 2 ] &&
  grep -qxF "act: warning: muscle 'flexor': its activation reaches 1.5; it acts as 1 (activations are clamped to [0, 1])" "$TMP/run"
ok $? "it warns once for each muscle out of range"
diag <"$TMP/run"
run --set strength=0.5
! grep -q "muscle 'flexor'" "$TMP/run" && grep -q "muscle 'extensor'" "$TMP/run"
ok $? "--set strength=0.5: the flexor is in range, nothing said of it"
run --set strength=-0.25
grep -qxF "act: warning: muscle 'flexor': its activation goes down to -0.25; it acts as 0 (activations are clamped to [0, 1])" "$TMP/run"
ok $? "--set strength=-0.25: below 0 is said too"

sed 's/^param strength = 1.5;/param strength = 0.8;/; s/ramp(0, 3, over/ramp(0, 1, over/' \
  "$TMP/act.sinew" >"$TMP/ok.sinew"
"$SC" "$TMP/ok.sinew" -o "$TMP/act" 2>"$TMP/err" && ! grep -q "activation" "$TMP/err"
ok $? "in range: sinewc says nothing of activations"
run; ! grep -q "warning" "$TMP/run"
ok $? "nor does the simulator"
done_testing
