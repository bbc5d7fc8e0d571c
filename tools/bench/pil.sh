#!/usr/bin/env bash
# pil.sh - what a processor-in-the-loop robot costs (make pil-avr-bench):
# each scenario of tests/pil/ run twice on one thread, every robot on an
# emulated ATmega2560 and every robot host-built; the difference, per PIL
# robot-step, in CPU time (the simulator's and its emulators', which run in
# turn: the simulator waits for each MCU's answer) and in wall time, and so
# how many PIL robots one core keeps at real time (the control period over
# that cost).  CPU time is counted from the kernel's figures for the run's
# processes (bash's `times`), so it holds on a busy machine; wall time does
# not.  PLATFORM=pil_m4 (make pil-m4-bench) puts the image robots on the
# emulated Cortex-M4F (QEMU) instead.  Usage: pil.sh [SWARMSIM] [SCENARIO...]
set -euo pipefail
cd "$(dirname "$0")/../.."
sim=${1:-build/swarmsim}
platform=${PLATFORM:-pil_avr}
shift || true
scenarios=("$@")
[ ${#scenarios[@]} -gt 0 ] || scenarios=(tests/pil/walk.yaml tests/pil/forage.yaml tests/pil/eaipp.yaml tests/pil/repatt.yaml)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# Children's user + system CPU seconds so far (bash's `times`, second line;
# the builtin runs in this shell, its output read back from a file).
children_cpu() {
    times > "$out/times"
    sed -n 2p "$out/times" | awk '{ n = 0; for (i = 1; i <= 2; i++) { split($i, a, "m"); n += a[1] * 60 + a[2] } printf "%.3f", n }'
}
# run NAME SCENARIO ARGS...: sets cpu, wall (s), robots, steps, period (ms)
# and pil (robots on the AVR); not in a subshell, so that `times` counts it.
run() {
    local name=$1 f=$2; shift 2
    local c0 c1 t0 t1
    children_cpu > "$out/c0"
    t0=$(date +%s.%N)
    "$sim" "$f" --quiet --threads 1 --lcm off --out "$out/$name" "$@" > "$out/$name.log" 2>&1 ||
        { echo "pil.sh: $f ($name) failed: $(tail -2 "$out/$name.log")" >&2; exit 1; }
    t1=$(date +%s.%N)
    children_cpu > "$out/c1"
    c0=$(cat "$out/c0") c1=$(cat "$out/c1")
    local s=("$out/$name"/run_*/summary.json)
    robots=$(sed -n 's/^  "robots": \([0-9]*\),/\1/p' "${s[0]}")
    steps=$(sed -n 's/^  "steps": \([0-9]*\),/\1/p' "${s[0]}")
    period=$(sed -n 's/^  "control_period_ms": \([0-9]*\),/\1/p' "${s[0]}")
    pil=$(sed -n 's/.*"pil": {"robots": \([0-9]*\).*/\1/p' "${s[0]}")
    pil=${pil:-0}
    cpu=$(awk -v a="$c0" -v b="$c1" 'BEGIN { printf "%.3f", b - a }')
    wall=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.3f", b - a }')
}

printf '%-10s %-7s %-7s %-8s %-10s %-10s %-15s %-15s %-16s\n' scenario robots steps period host_cpu_s pil_cpu_s "us/PIL-step" "us/step(wall)" "PIL robots/core"
for f in "${scenarios[@]}"; do
    name=$(basename "$f" .yaml)

    all=() host=()
    g=0
    while read -r line; do
        all+=(--set "robots.$g.platform_robots=0")
        case $line in *"platform: pil_avr"*) all+=(--set "robots.$g.platform=$platform") ;; esac
        host+=(--set "robots.$g.platform=host")
        g=$((g + 1))
    done < <(grep 'controller:' "$f")
    run "$name.host" "$f" "${host[@]}"
    hc=$cpu hw=$wall
    # Groups without an image stay host-built: count the PIL robots the run reports.
    run "$name.pil" "$f" "${all[@]}"
    pc=$cpu pw=$wall
    [ "$pil" -gt 0 ] || { echo "pil.sh: $f: no robot ran on $platform" >&2; exit 1; }
    awk -v n="$name" -v r="$robots" -v s="$steps" -v p="$period" -v hc="$hc" -v pc="$pc" -v hw="$hw" -v pw="$pw" -v k="$pil" 'BEGIN {
        c = (pc - hc) / (k * s); w = (pw - hw) / (k * s)
        printf "%-10s %-7s %-7s %-8s %-10.2f %-10.2f %-15.1f %-15.1f %-16d\n", n, k "/" r, s, p " ms", hc, pc, c * 1e6, w * 1e6, (p / 1000) / c
    }'
done
echo "platform: $platform; machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), load $(cut -d' ' -f1-3 /proc/loadavg)"
