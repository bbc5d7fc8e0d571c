#!/usr/bin/env bash
# telemetry_options.sh - swarmsim's LCM telemetry options: the default log
# is bit-identical for 1 and 2 threads (simulated-time stamps, no wall
# clock); telemetry never changes a run's results; --lcm off writes no log;
# --lcm URL publishes instead of logging; bad --telemetry-rate / --realtime
# values are usage errors (exit 2, nothing written).
set -u
sim=${1:-build/swarmsim}
cd "$(dirname "$0")/../.."
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0
# Byte for byte but the "command" line: its provenance names the options.
same() { cmp -s <(grep -v '^  "command": ' "$1") <(grep -v '^  "command": ' "$2"); }
check() { if eval "$2"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL: $1"; fi; }

args=(sim_host/scenarios/foraging_base.yaml --steps 800 --reps 3 --quiet)
"$sim" "${args[@]}" --threads 1 --out "$tmp/t1"
"$sim" "${args[@]}" --threads 2 --out "$tmp/t2"
"$sim" "${args[@]}" --threads 2 --out "$tmp/off" --lcm off
"$sim" "${args[@]}" --threads 2 --out "$tmp/fast" --telemetry-rate 10,10
for seed in 1 2 3; do
    check "run_$seed telemetry.lcmlog differs between 1 and 2 threads" \
        "cmp -s '$tmp/t1/run_$seed/telemetry.lcmlog' '$tmp/t2/run_$seed/telemetry.lcmlog'"
    check "run_$seed: telemetry changed the summary" "same '$tmp/t1/run_$seed/summary.json' '$tmp/off/run_$seed/summary.json'"
    check "run_$seed: a higher telemetry rate changed the summary" \
        "same '$tmp/t1/run_$seed/summary.json' '$tmp/fast/run_$seed/summary.json'"
    check "run_$seed: --lcm off wrote a log" "[ ! -e '$tmp/off/run_$seed/telemetry.lcmlog' ]"
    check "run_$seed: a temporary file was left" "[ -z \"\$(ls '$tmp/t1/run_$seed' | grep tmp)\" ]"
done
check "runs 1 and 2 have the same log" "! cmp -s '$tmp/t1/run_1/telemetry.lcmlog' '$tmp/t1/run_2/telemetry.lcmlog'"
check "--telemetry-rate 10 did not make a larger log" \
    "[ \$(stat -c %s '$tmp/fast/run_1/telemetry.lcmlog') -gt \$(stat -c %s '$tmp/t1/run_1/telemetry.lcmlog') ]"

# A URL instead of the log file (memq: in-process, nobody listening).
"$sim" sim_host/scenarios/random_walk.yaml --steps 100 --quiet --out "$tmp/memq" --lcm memq://
check "--lcm memq:// failed" "[ $? -eq 0 ]"
check "--lcm URL wrote a log file" "[ ! -e '$tmp/memq/run_1/telemetry.lcmlog' ] && [ -e '$tmp/memq/run_1/summary.json' ]"
"$sim" sim_host/scenarios/random_walk.yaml --steps 100 --quiet --out "$tmp/badurl" --lcm nosuch://x 2>"$tmp/err"
check "a bad --lcm URL is not a setup error (exit 2) naming the URL, with no folder" \
    "[ $? -eq 2 ] && grep -q 'nosuch://x' '$tmp/err' && [ ! -e '$tmp/badurl' ]"
"$sim" sim_host/scenarios/random_walk.yaml --steps 100 --quiet --out "$tmp/rt_off" --lcm off --realtime 2 2>"$tmp/err"
check "--realtime with --lcm off is not an error (exit 2) saying why, with no folder" \
    "[ $? -eq 2 ] && grep -q 'nothing to watch' '$tmp/err' && [ ! -e '$tmp/rt_off' ]"

# --realtime paces: 20 steps of 100 ms at 10x take at least 0.2 s.
start=$(date +%s%N)
"$sim" sim_host/scenarios/random_walk.yaml --steps 20 --quiet --out "$tmp/rt" --realtime 10
took=$(( ($(date +%s%N) - start) / 1000000 ))
check "--realtime 10 ran 2 s of simulated time in ${took} ms" "[ $took -ge 190 ]"

for bad in "--telemetry-rate -1" "--telemetry-rate 1,x" "--telemetry-rate ''" "--realtime 0" "--realtime fast"; do
    eval "\"$sim\" sim_host/scenarios/random_walk.yaml --steps 10 --out '$tmp/bad' $bad" 2>"$tmp/err"
    rc=$?
    check "$bad: exit $rc, not 2" "[ $rc -eq 2 ]"
    check "$bad: no message" "[ -s '$tmp/err' ]"
    check "$bad: wrote output" "[ ! -e '$tmp/bad' ]"
done
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
