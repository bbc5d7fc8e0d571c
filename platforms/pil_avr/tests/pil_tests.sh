#!/usr/bin/env bash
# pil_tests.sh - the emulated ATmega2560's tests (platform.mk's pil-avr-tests
# and pil-avr-compare):
#  1. every image (IMAGES) on the AVR beside its host build, STEPS steps over
#     a scripted world, compared request by request and frame by frame; the
#     images of FRAMES once more with RGB565 camera frames (blob_detect on the
#     MCU) for 60 steps; with LONG set (make pil-avr-compare), each over two
#     robots and seeds, the frames' runs for STEPS too;
#  2. every protocol error and every way an MCU fails (a damaged frame from
#     the simulator, the misbehaving test image, a killed or hung emulator):
#     each must be an error naming the robot and the step, within bounds;
#  3. with REPORT set, the measured cycles and stack per image, as a table.
# With M4_OUT set (platforms/pil_m4/platform.mk: pil-m4-tests), the same on
# the emulated Cortex-M4F (QEMU): every image's M4 ELF in M4_OUT/m4/ beside
# the same host build, its counts instructions; the misbehaving image's
# chip-specific faults are that chip's (tests/misbehave_main.c).
set -u
. "$(dirname "$0")/../../../tests/lib/wait_until.sh"
out=${PIL_OUT:?}
m4=${M4_OUT:-}
chip=$([ -n "$m4" ] && echo pil-m4 || echo pil-avr)
steps=${STEPS:-150}
cmp=$out/pil_compare
emu=$out/pil_avr_emu
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
measure=${m4:-$out}/measure
mkdir -p "$measure"
rm -f "$measure"/*.json
# mcu IMAGE: the driver's options that run the image on this chip.
mcu() { if [ -n "$m4" ]; then echo "--m4 $m4/m4/$1.elf"; else echo "--emu $emu --avr $out/avr/$1.elf"; fi; }

compare() {   # IMAGE ROBOT SEED [--frames]
    local img=$1 robot=$2 seed=$3; shift 3
    local tag=$img${1:+_frames}
    # shellcheck disable=SC2046
    if msg=$("$cmp" $(mcu "$img") --host "$out/host/$img" --steps "${steps:-150}" \
                 --robot "$robot" --seed "$seed" --json "$measure/${tag}_$robot.json" "$@" 2>&1); then
        ok; echo "$msg" | tail -1
    else
        bad "$img (robot $robot, seed $seed $*): $msg"
    fi
}

# A second robot and seed, and the camera frames' runs, when LONG is set
# (make pil-avr-compare); make test's short run: one robot, frames for 60 steps.
for img in $IMAGES; do
    compare "$img" 3 1
    [ -n "${LONG:-}" ] && compare "$img" 11 7
done
for img in $FRAMES; do
    if [ -n "${LONG:-}" ]; then
        compare "$img" 3 1 --frames
        compare "$img" 11 7 --frames
    else
        steps=60 compare "$img" 3 1 --frames
    fi
done

# Errors: each run must fail with the expected words in its error, which
# names the robot and the step.
expect() {   # WORDS ARGS...
    local words=$1; shift
    if msg=$("$cmp" --steps 20 "$@" --expect "$words" 2>&1); then
        case $msg in
            *"robot "*", step "*) ok ;;
            *) bad "error without robot and step ($*): $msg" ;;
        esac
    else
        bad "$*: $msg"
    fi
}
read -r -a rw <<< "$(mcu random_walk)"
read -r -a mis <<< "$(mcu misbehave)"
# What the chips name differently: a halt (the M4 just sleeps: the
# wall-time bound).
if [ -n "$m4" ]; then
    halt=(--timeout 2000) halt_words="step 3: its emulator gave no answer within 2000 ms"
    expect "step 0: its MCU ran past its cycle budget" "${rw[@]}" --budget 2000
    # The counts count instructions: a step of 100,001 between the marks
    # (tests/calibrate_main.c) reads that, plus a mark's few, to the
    # SysTick's resolution of about 6.
    if "$cmp" --m4 "$m4/m4/calibrate.elf" --steps 5 --json "$m4/calibrate.json" > /dev/null 2>&1 \
        && python3 -c 'import json, sys; m = json.load(open(sys.argv[1])); sys.exit(not 100001 <= m["control_mean"] <= m["control_max"] <= 100060)' \
            "$m4/calibrate.json" 2> /dev/null; then
        ok
    else
        bad "the calibration image's 100,001 instructions: $(cat "$m4/calibrate.json" 2>/dev/null)"
    fi
else
    halt=() halt_words="step 3: its MCU halted"
fi
expect "step 3: its MCU crashed" "${mis[@]}" --robot 1
expect "step 3: its MCU ran past its cycle budget" "${mis[@]}" --robot 2 --budget 200000
expect "step 3: its MCU reset" "${mis[@]}" --robot 3
expect "step 3: its MCU overflowed its stack" "${mis[@]}" --robot 4
expect "step 3: sent a frame with a bad CRC" "${mis[@]}" --robot 5
expect "$halt_words" "${mis[@]}" --robot 6 "${halt[@]}"
expect "step 3: sent a REQUEST that does not decode" "${mis[@]}" --robot 7
expect "step 3: sent 2 IR messages in one period" "${mis[@]}" --robot 8
expect "step 3: sent a ACT frame of step" "${mis[@]}" --robot 9
# A well-behaved robot of the misbehaving image runs to the end.
if "$cmp" "${mis[@]}" --robot 0 --steps 20 > /dev/null 2>&1; then ok; else bad "misbehave robot 0 failed"; fi
for kind in crc version type seq length; do
    expect "step 5: could not read the simulator's last frame (FAULT" "${rw[@]}" --corrupt "5:$kind"
done
expect "step 4: its emulator was killed by signal 9" "${rw[@]}" --kill-at 4
expect "step 4: its emulator gave no answer within 2000 ms" "${rw[@]}" --stop-at 4 --timeout 2000
# No emulator outlives the simulator: kill the driver mid-run (SIGKILL, no
# clean-up of its own) and wait for its emulator to go (PR_SET_PDEATHSIG).
"$cmp" "${rw[@]}" --steps 100000000 > /dev/null 2>&1 &
driver=$!
child=""
wait_until 120 'child=$(pgrep -P "$driver" 2>/dev/null | head -1); [ -n "$child" ]'
if [ -z "$child" ]; then
    bad "the driver started no emulator"
    kill -9 "$driver" 2>/dev/null
else
    kill -9 "$driver"
    wait "$driver" 2>/dev/null
    wait_until 120 '! kill -0 "$child" 2>/dev/null'
    if kill -0 "$child" 2>/dev/null; then bad "the emulator outlived its simulator"; kill -9 "$child"; else ok; fi
fi

if [ -n "${REPORT:-}" ] && [ -z "$m4" ]; then
    for d in blobs:0 tones:1; do
        if "$cmp" --emu "$emu" --avr "$out/avr/detect.elf" --robot "${d#*:}" --steps 30 \
               --json "$out/measure/detect_${d%:*}.json" --cycles "$out/measure/detect_${d%:*}.csv" > /dev/null; then
            ok
        else
            bad "the detector image (${d%:*})"
        fi
    done
    python3 "$(dirname "$0")/pil_report.py" "$out/measure" --cpu "$out/../cpu.md" \
        --footprint "$out/../epuck1/footprint.md" > "$REPORT.tmp" && mv "$REPORT.tmp" "$REPORT" \
        && { ok; echo "pil-avr: measured cycles and stack: $REPORT"; } || bad "the report"
fi
echo "$chip: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
