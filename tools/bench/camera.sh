#!/usr/bin/env bash
# camera.sh - the camera models' cost: one robot-frame of each (camera_bench)
# and the real-time factor of seed 000's base scenario (1200 s, one thread,
# no telemetry) with the geometric camera (at the robot's 4.3 fps, the
# default, and every step) and the rendered one; medians of 5 runs each.
# Usage: camera.sh [SWARMSIM] [CAMERA_BENCH]
set -euo pipefail
cd "$(dirname "$0")/../.."
sim=${1:-build/swarmsim}
bench=${2:-build/camera_bench}
scenario=sim_host/scenarios/foraging_base.yaml
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

"$bench" "$scenario" 5 100 1200
median() { sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
printf '%-34s %-10s %-10s\n' "seed 000 base, camera" wall_s real_time_x
for spec in "geometric, 4.3 fps (default):" "geometric, every step:--set camera.fps=0" "rendered, 4.3 fps:--set camera.model=rendered"; do
    name=${spec%%:*} args=${spec#*:}
    walls=() rtfs=()
    for k in 1 2 3 4 5; do
        # shellcheck disable=SC2086
        line=$("$sim" "$scenario" --threads 1 --lcm off --out "$out/$k" --replace $args 2>&1 >/dev/null | grep 'x real time')
        walls+=("$(sed -E 's/.* in ([0-9.]+) s wall.*/\1/' <<<"$line")")
        rtfs+=("$(sed -E 's/.*, ([0-9]+)x real time.*/\1/' <<<"$line")")
    done
    printf '%-34s %-10s %-10s\n' "$name" "$(printf '%s\n' "${walls[@]}" | median)" "$(printf '%s\n' "${rtfs[@]}" | median)"
done
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'); load $(cut -d' ' -f1-3 /proc/loadavg)"
