#!/usr/bin/env bash
# determinism.sh - same seed, identical output bytes, whatever --threads
# (runs side by side) or --run-threads (threads inside a run).
# Runs 4 repetitions of a short default-scenario run with 1 and with 2
# threads and compares every summary.json (but its command line) and
# timeseries.csv byte for byte;
# a different seed must give different bytes (else the check proves nothing).
set -u
sim=${1:-build/swarmsim}
cd "$(dirname "$0")/../.."
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0
check() { if eval "$2"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL: $1"; fi; }
# Byte for byte but the "command" line: its provenance names --threads and --out.
same() { cmp -s <(grep -v '^  "command": ' "$1") <(grep -v '^  "command": ' "$2"); }

args=(sim_host/scenarios/random_walk.yaml --steps 1500 --reps 4 --quiet --set wheels.speed_noise_rel=0.05)
"$sim" "${args[@]}" --threads 1 --out "$tmp/t1"
"$sim" "${args[@]}" --threads 2 --out "$tmp/t2"
"$sim" "${args[@]}" --threads 1 --out "$tmp/s2" --seed 2

for seed in 1 2 3 4; do
    for f in summary.json timeseries.csv; do
        check "run_$seed/$f differs between 1 and 2 threads" "same '$tmp/t1/run_$seed/$f' '$tmp/t2/run_$seed/$f'"
    done
done
check "aggregate summary differs between 1 and 2 threads" "same '$tmp/t1/summary.json' '$tmp/t2/summary.json'"
check "seeds 1 and 2 gave the same run" "! same '$tmp/t1/run_1/summary.json' '$tmp/t1/run_2/summary.json'"
# --seed 2 makes rep 0 use seed 2: identical to rep 1 of the --seed 1 run.
check "--seed 2 run_2 differs from --seed 1 run_2" "same '$tmp/t1/run_2/summary.json' '$tmp/s2/run_2/summary.json'"
# The foraging task (beacon, tokens, ledger) with both thread counts.
fargs=(sim_host/scenarios/foraging_base.yaml --steps 2000 --reps 3 --quiet)
"$sim" "${fargs[@]}" --threads 1 --out "$tmp/f1"
"$sim" "${fargs[@]}" --threads 2 --out "$tmp/f2"
# Inside a run: chunks of a few robots (pool.h's test hook), so that 21
# robots are stepped on 3 threads at once.
SWARMSIM_POOL_CHUNK=1 "$sim" "${fargs[@]}" --threads 1 --run-threads 3 --out "$tmp/f3"
for seed in 1 2 3; do
    for f in summary.json timeseries.csv; do
        check "foraging run_$seed/$f differs between 1 and 2 threads" "same '$tmp/f1/run_$seed/$f' '$tmp/f2/run_$seed/$f'"
        check "foraging run_$seed/$f differs with 3 threads inside the run" "same '$tmp/f1/run_$seed/$f' '$tmp/f3/run_$seed/$f'"
    done
done
# RepAtt with sound on (seed 002): eq 4's noise drawn per listener, in both
# listening schedules (the paper's duplex; slotted with self-masking).
for mode in duplex slotted; do
    rargs=(sim_host/scenarios/repatt_quick.yaml --steps 4000 --reps 3 --quiet --set robots.0.params.listening=$mode)
    [ $mode = slotted ] && rargs+=(--set sound.self_masking=true)
    "$sim" "${rargs[@]}" --threads 1 --out "$tmp/r1$mode"
    "$sim" "${rargs[@]}" --threads 2 --out "$tmp/r2$mode"
    for seed in 1 2 3; do
        for f in summary.json timeseries.csv; do
            check "repatt ($mode) run_$seed/$f differs between 1 and 2 threads" "same '$tmp/r1$mode/run_$seed/$f' '$tmp/r2$mode/run_$seed/$f'"
        done
    done
    check "repatt ($mode): seeds 1 and 2 gave the same run" "! same '$tmp/r1$mode/run_1/timeseries.csv' '$tmp/r1$mode/run_2/timeseries.csv'"
done
# Path formation (seed 003): EAIPP over the turret with collisions, packet
# loss, the bearing-noise vector and wheel bias, with random cylinders.
eargs=(sim_host/scenarios/eaipp_square.yaml --steps 3000 --reps 3 --quiet --set random_cylinders.count=10
       --set ircom.loss=0.2 --set ircom.bearing_noise_vec=0.05 --set wheels.bias_sd=0.01)
"$sim" "${eargs[@]}" --threads 1 --out "$tmp/e1"
"$sim" "${eargs[@]}" --threads 2 --out "$tmp/e2"
SWARMSIM_POOL_CHUNK=1 "$sim" "${eargs[@]}" --threads 1 --run-threads 2 --out "$tmp/e3"
for seed in 1 2 3; do
    for f in summary.json timeseries.csv; do
        check "eaipp run_$seed/$f differs between 1 and 2 threads" "same '$tmp/e1/run_$seed/$f' '$tmp/e2/run_$seed/$f'"
        check "eaipp run_$seed/$f differs with 2 threads inside the run" "same '$tmp/e1/run_$seed/$f' '$tmp/e3/run_$seed/$f'"
    done
done
check "eaipp: seeds 1 and 2 gave the same run" "! same '$tmp/e1/run_1/timeseries.csv' '$tmp/e1/run_2/timeseries.csv'"
check "state hash missing" "grep -q state_hash '$tmp/t1/run_1/summary.json'"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
