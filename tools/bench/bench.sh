#!/usr/bin/env bash
# bench.sh - simulator throughput: robot-steps per second and real-time
# factor for 20, 200 and 2,000 random-walking e-pucks at constant density
# (1.25 robots/m^2), one thread, no pictures, telemetry at its default
# (an LCM log per run).  Usage: [BENCH_ARGS="--lcm off"] bench.sh [SWARMSIM]
set -euo pipefail
cd "$(dirname "$0")/../.."
sim=${1:-build/swarmsim}
scenario=tools/bench/bench_random_walk.yaml
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

printf '%-8s %-10s %-8s %-12s %-16s %-14s\n' robots arena_m steps wall_s robot_steps/s real_time_x
for spec in 20:12000 200:6000 2000:1500; do
    n=${spec%%:*} steps=${spec##*:}
    side=$(awk -v n="$n" 'BEGIN { printf "%.3f", sqrt(n / 1.25) }')
    line=$("$sim" "$scenario" --threads 1 --steps "$steps" --out "$out/$n" \
        --set robots.0.count="$n" --set arena.width="$side" --set arena.height="$side" ${BENCH_ARGS:-} 2>&1 >/dev/null |
        grep 'robot-steps/s')
    wall=$(sed -E 's/.* in ([0-9.]+) s wall.*/\1/' <<<"$line")
    rate=$(sed -E 's/.*: ([0-9]+) robot-steps\/s.*/\1/' <<<"$line")
    rtf=$(sed -E 's/.*, ([0-9]+)x real time.*/\1/' <<<"$line")
    printf '%-8s %-10s %-8s %-12s %-16s %-14s\n' "$n" "$side" "$steps" "$wall" "$rate" "$rtf"
done
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
