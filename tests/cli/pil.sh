#!/usr/bin/env bash
# pil.sh - processor-in-the-loop in the simulator (docs/reference/pil.md):
#  1. every controller family's test scenario (tests/pil/*.yaml), with some
#     robots on emulated ATmega2560s running their images' machine code,
#     ends in the same state hash as the same scenario host-built (every
#     group's platform set to host); the foragers' LCM log, their images'
#     own telemetry frames included, is the same bytes; on 3 run threads
#     the same hash as on 1;
#  2. what can go wrong is an error naming the robot and the step, exit 1
#     and no run folder (a step past its cycle budget, an emulator that
#     stops answering, exits or hangs, a stale image), or a setup error
#     (exit 2, nothing written: no emulator, an image that is not the one
#     named, an image built for other IR messages);
#  3. no emulator outlives a killed simulator;
#  4. mixed swarms: some robots on the AVR, some on the emulated Cortex-M4F
#     (QEMU, platforms/pil_m4/), the rest host-built: the host-built hash;
#     the M4's errors (its budget, no QEMU) name robot and step.
# The emulated robots need make pil-avr's and pil-m4's builds
# (build/firmware/pil_avr/ and pil_m4/, beside swarmsim: make cli-tests
# builds them).  (About 40 s.)
#
# usage (from the repository root): bash tests/cli/pil.sh build/swarmsim
set -u
sim=${1:-build/swarmsim}
case $sim in /*) ;; *) sim="$PWD/$sim" ;; esac
cd "$(dirname "$0")/../.." || exit 1
. tests/lib/wait_until.sh
pil=$(dirname "$sim")/firmware/pil_avr
tmp=$(mktemp -d "${TMPDIR:-/tmp}/pil.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
hash_of() { sed -n 's/.*"state_hash": "\([0-9a-f]*\)".*/\1/p' "$1"/run_*/summary.json; }
groups_of() { grep -c 'controller:' "$1"; }

# ---- 1. the same swarm, bit for bit
for f in tests/pil/*.yaml; do
    name=$(basename "$f" .yaml)
    host=()
    for ((g = 0; g < $(groups_of "$f"); g++)); do host+=(--set "robots.$g.platform=host"); done
    if ! "$sim" "$f" --quiet --threads 1 --out "$tmp/$name.pil" > "$tmp/$name.pil.log" 2>&1; then
        bad "$name on the AVR: $(tail -2 "$tmp/$name.pil.log")"
        continue
    fi
    if ! "$sim" "$f" --quiet --threads 1 --out "$tmp/$name.host" "${host[@]}" > "$tmp/$name.host.log" 2>&1; then
        bad "$name host-built: $(tail -2 "$tmp/$name.host.log")"
        continue
    fi
    a=$(hash_of "$tmp/$name.pil") b=$(hash_of "$tmp/$name.host")
    robots=$(sed -n 's/.*"pil": {"robots": \([0-9]*\).*/\1/p' "$tmp/$name.pil"/run_*/summary.json)
    if [ -n "$a" ] && [ "$a" = "$b" ] && [ "${robots:-0}" -gt 0 ]; then
        ok
        echo "pil: $name: $robots robots on the AVR, state hash $a as host-built"
    else
        bad "$name: state hash $a with ${robots:-no} robots on the AVR, $b host-built"
    fi
done
# PFIAS and TSASR share a world (tests/pil/pfias.yaml, tsasr.yaml): TSASR,
# PFIAS's chains with a timed elimination, must eliminate in it and end
# elsewhere (the same hash would mean the images ran the same controller).
elims=$(sed -n 's/.*"eliminations_total": \([0-9]*\).*/\1/p' "$tmp"/tsasr.pil/run_*/summary.json | head -1)
if [ -n "$(hash_of "$tmp/tsasr.pil")" ] && [ "$(hash_of "$tmp/tsasr.pil")" != "$(hash_of "$tmp/pfias.pil")" ] \
    && [ "${elims:-0}" -gt 0 ]; then
    ok
else
    bad "tsasr against pfias on the AVR: hashes $(hash_of "$tmp/tsasr.pil") and $(hash_of "$tmp/pfias.pil"), ${elims:-no} eliminations"
fi
# The PIL robots' steps on the run's worker threads: the same hash on 3
# (its phototaxis robots on the M4: both chips' links from worker threads).
if "$sim" tests/pil/walk.yaml --quiet --threads 1 --run-threads 3 --out "$tmp/walk.t3" --set robots.1.platform=pil_m4 \
    > "$tmp/walk.t3.log" 2>&1 \
    && [ -n "$(hash_of "$tmp/walk.pil")" ] && [ "$(hash_of "$tmp/walk.t3")" = "$(hash_of "$tmp/walk.pil")" ]; then
    ok
else
    bad "walk on 3 run threads: state hash $(hash_of "$tmp/walk.t3"), on 1: $(hash_of "$tmp/walk.pil")"
fi
if cmp -s "$tmp"/forage.pil/run_*/telemetry.lcmlog "$tmp"/forage.host/run_*/telemetry.lcmlog \
    && grep -qa FW_ROBOT_STATE "$tmp"/forage.pil/run_*/telemetry.lcmlog; then
    ok
else
    bad "the foragers' LCM log (their images' own FW_ROBOT_STATE frames) differs between the AVR and the host build"
fi

# ---- 1, mixed (4 above): AVR, M4 and host-built robots in one run
for mix in "walk robots.1.platform=pil_m4" "forage robots.1.platform=pil_m4"; do
    set -- $mix
    name=$1
    if ! "$sim" "tests/pil/$name.yaml" --quiet --threads 1 --out "$tmp/$name.mix" --set "$2" > "$tmp/$name.mix.log" 2>&1; then
        bad "$name mixed (AVR, M4, host): $(tail -2 "$tmp/$name.mix.log")"
        continue
    fi
    a=$(hash_of "$tmp/$name.mix") b=$(hash_of "$tmp/$name.host")
    m4=$(sed -n 's/.*"pil_m4": {"robots": \([0-9]*\).*/\1/p' "$tmp/$name.mix"/run_*/summary.json)
    if [ -n "$a" ] && [ "$a" = "$b" ] && [ "${m4:-0}" -gt 0 ]; then
        ok
        echo "pil: $name: AVR, ${m4} on the M4 and host-built robots, state hash $a as host-built"
    else
        bad "$name mixed: state hash $a with ${m4:-no} robots on the M4, $b host-built"
    fi
done
if [ "$name" = forage ] && cmp -s "$tmp"/forage.mix/run_*/telemetry.lcmlog "$tmp"/forage.host/run_*/telemetry.lcmlog; then
    ok
else
    bad "the mixed foragers' LCM log differs from the host build's"
fi

# ---- 2. errors: robot and step named, nothing written
fails() {   # WHAT STATUS WORDS ARGS... : swarmsim exits STATUS with WORDS, no run folder
    local what=$1 status=$2 words=$3; shift 3
    local out="$tmp/err.$pass.$fail"
    "$sim" "$@" --quiet --threads 1 --lcm off --out "$out" > "$tmp/err.log" 2>&1
    local rc=$?
    if [ "$rc" -ne "$status" ]; then
        bad "$what: exit $rc, not $status: $(tail -2 "$tmp/err.log")"
    elif ! grep -q -- "$words" "$tmp/err.log"; then
        bad "$what: no \"$words\" in: $(tail -2 "$tmp/err.log")"
    elif compgen -G "$out/run_*/summary.json" > /dev/null; then
        bad "$what: a run folder was written"
    else
        ok
    fi
}
walk=tests/pil/walk.yaml
fails "a step past its cycle budget" 1 "robot 0 (image random_walk on pil_avr), step 0: its MCU ran past its cycle budget" \
    "$walk" --set pil.cycle_budget=3000
fails "a boot past its budget" 2 "robot 0 (robots.0, image random_walk on pil_avr), boot: its MCU ran past its cycle budget" \
    "$walk" --set pil.boot_budget=5000
# Emulators that misbehave: a copy of the build whose emulator is a script.
fake() {   # NAME BODY: a pil dir whose pil_avr_emu runs BODY
    mkdir -p "$tmp/$1"
    cp -r "$pil/avr" "$tmp/$1/avr"
    printf '#!/usr/bin/env bash\n%s\n' "$2" > "$tmp/$1/pil_avr_emu"
    chmod +x "$tmp/$1/pil_avr_emu"
}
fake eof "dd bs=1 count=3000 status=none | \"$pil/pil_avr_emu\" \"\$@\""
fails "an emulator that stops in the middle of the run" 1 "robot [0-9]* (image [a-z_]* on pil_avr), step [0-9]*: its emulator exited" \
    "$walk" --set "pil.dir=$tmp/eof"
fake hang "exec sleep 600"
fails "an emulator that never answers" 2 "robot 0 (robots.0, image random_walk on pil_avr), boot: its emulator gave no answer within 500 ms" \
    "$walk" --set "pil.dir=$tmp/hang" --set pil.boot_timeout_s=0.5
fake stale "exec \"$pil/pil_avr_emu\" \"\$@\""
cp "$pil/avr/phototaxis.elf" "$tmp/stale/avr/random_walk.elf"
fails "an image that is another" 2 "its ELF says it is image phototaxis" "$walk" --set "pil.dir=$tmp/stale"
fails "no emulator" 2 "the AVR emulator $tmp/none/pil_avr_emu" "$walk" --set "pil.dir=$tmp/none"
fails "an image built for other IR messages" 2 "the image sends 8-bit IR messages, the scenario's ircom.payload_bits is 16" \
    "$walk" --set ircom.payload_bits=16
fails "an M4 step past its budget" 1 "robot 0 (image random_walk on pil_m4), step 0: its MCU ran past its cycle budget without answering after 3000 instructions" \
    "$walk" --set robots.0.platform=pil_m4 --set pil.cycle_budget=3000
printf '#!/bin/sh\nPATH=/nonexistent exec "%s" "$@"\n' "$sim" > "$tmp/noqemu" && chmod +x "$tmp/noqemu"
sim_real=$sim sim=$tmp/noqemu
fails "no QEMU" 2 "robot 0 (robots.0, image random_walk on pil_m4), boot: its emulator qemu-system-arm (Debian's qemu-system-arm) could not be started" \
    "$walk" --set robots.0.platform=pil_m4
sim=$sim_real
fails "a PIL group without an image" 2 "runs a robot image: give image: NAME" \
    sim_host/scenarios/random_walk.yaml --set robots.0.platform=pil_avr

# ---- 3. no emulator outlives the simulator (AVR emulators and QEMUs)
"$sim" "$walk" --quiet --threads 1 --lcm off --steps 1000000000 --out "$tmp/killed" --set robots.1.platform=pil_m4 \
    > /dev/null 2>&1 &
run=$!
children=""
wait_until 120 'children=$(pgrep -P "$run" 2>/dev/null | tr "\n" " "); [ "$(echo "$children" | wc -w)" -ge 4 ]'
kill -9 "$run" 2>/dev/null
wait "$run" 2>/dev/null
if [ -z "$children" ]; then
    bad "the simulator started no emulator"
else
    gone() { for c in $children; do kill -0 "$c" 2>/dev/null && return 1; done; return 0; }
    if wait_until 120 gone; then ok; else bad "an emulator outlived its killed simulator"; kill -9 $children 2>/dev/null; fi
fi

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
