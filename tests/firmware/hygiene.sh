#!/usr/bin/env bash
# hygiene.sh - checks the firmware rules on the compiled objects:
#  1. every firmware and platform-neutral HAL source compiles warning-free as
#     C99 on the host and with avr-gcc (16-bit int and pointers, 32-bit
#     double: the data model of XC16 on the dsPIC);
#  2. no object has writable static data (.data/.bss non-empty or data
#     symbols): controllers keep all state in their structs;
#  3. nothing calls malloc/calloc/realloc/free;
#  4. no conditional compilation in controllers except include guards;
#  5. layering: controllers read only hal/*.h, firmware/ and lcm-gen's
#     headers (not the simulator, not platforms/epuck1/hal);
#  6. parameter descriptors whose type does not match their field do not
#     compile.
# platforms/epuck1/hal (the e-puck1 HAL) obeys rules 1-3 too: its state is the
# caller's struct hal.  The images' mains (firmware/apps) compile under rule
# 1 and call no allocator; their static variables are the one documented
# exception (no heap on the robot, main never returns): only the robot's
# struct hal (app_hal), the controller (app_*) and the camera frames
# (camera_frames) may be writable statics there; app_* includes the
# telemetry sender and its buffers (app_telemetry).
# The checker is itself checked on a bad source that must be caught.
set -u
cd "$(dirname "$0")/../.."
out=build/fw
mkdir -p "$out/host" "$out/avr"
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }

srcs=$(ls firmware/*/*.c hal/*.c wire/*/*.c platforms/epuck1/hal/*.c | grep -v '^firmware/apps/')
# Firmware sees hal/, firmware/ and lcm-gen's headers (for the robot's own
# telemetry) only.  -fno-pie: const tables of pointers stay in .rodata.
flags="-std=c99 -pedantic -Wall -Wextra -Werror -Wshadow -Wstrict-prototypes -Wmissing-prototypes -Ihal -Iwire -Ifirmware -Iplatforms/epuck1/hal -I${LCM_C_DIR:-build/lcm_c} ${LCM_CFLAGS:-}"

# Writable static data in one object: prints what it finds.
writable() {
    local o=$1
    size -A "$o" | awk '$1 ~ /^\.(data|bss)(\.|$)/ && $2 > 0 { print "section " $1 " has " $2 " bytes" }'
    nm "$o" | awk '$2 ~ /^[dDbBC]$/ { print "writable symbol " $3 }'
}
allocates() { nm -u "$1" | awk '$2 ~ /^(malloc|calloc|realloc|free)$/ { print "calls " $2 }'; }

for src in $srcs; do
    name=$(basename "${src%.c}")
    obj="$out/host/$name.o"
    if ! cc $flags -fno-pie -O2 -c "$src" -o "$obj"; then bad "$src does not compile on the host"; continue; fi
    ok
    w=$(writable "$obj")
    if [ -n "$w" ]; then bad "$src: writable static data: $w"; else ok; fi
    a=$(allocates "$obj")
    if [ -n "$a" ]; then bad "$src: $a"; else ok; fi
    if avr-gcc -mmcu=atmega128 $flags -Os -c "$src" -o "$out/avr/$name.o"; then ok
    else bad "$src does not compile warning-free with avr-gcc (16-bit int)"; fi
done

# Images (firmware/apps): warning-free on both, no allocator, and no
# writable statics but the documented ones.  They include lcm-gen's headers
# (LCM_C_DIR, from make lcm-types) and LCM's (LCM_CFLAGS).
apps=$(ls firmware/apps/*.c)
appflags="$flags"
for src in $apps; do
    name=app_$(basename "${src%.c}")
    obj="$out/host/$name.o"
    if ! cc $appflags -O2 -c "$src" -o "$obj"; then bad "$src does not compile on the host"; continue; fi
    ok
    if avr-gcc -mmcu=atmega128 $appflags -Os -c "$src" -o "$out/avr/$name.o"; then ok
    else bad "$src does not compile warning-free with avr-gcc (16-bit int)"; fi
    w=$(nm "$obj" | awk '$2 ~ /^[dDbBC]$/ { print $3 }' | grep -vE '^(app_[A-Za-z0-9_]+|camera_frames)(\.[0-9]+)?$')
    if [ -n "$w" ]; then bad "$src: undocumented writable statics: $w"; else ok; fi
    a=$(allocates "$obj")
    if [ -n "$a" ]; then bad "$src: $a"; else ok; fi
done

# Controllers: no #if/#ifdef other than the include guard of a header.
for f in $(ls firmware/*/*.[ch] | grep -v '^firmware/apps/'); do
    n=$(grep -cE '^\s*#\s*(if|ifdef|ifndef|elif)\b' "$f")
    guard=0
    case "$f" in *.h) guard=1 ;; esac
    if [ "$n" -gt "$guard" ]; then bad "$f: conditional compilation in a controller"; else ok; fi
done

# Layering: a controller depends on hal/*.h (the contract and its
# platform-neutral helpers), firmware/ and lcm-gen's headers only; never on
# the simulator or a platform (platforms/epuck1/hal).  `cc -M` lists every header a
# source really reads, relative includes too.
ctrl_flags="-std=c99 -Ihal -Iwire -Ifirmware -I${LCM_C_DIR:-build/lcm_c} ${LCM_CFLAGS:-}"
lcm_dirs=$(echo "${LCM_CFLAGS:-}" | awk '{ for (i = 1; i <= NF; i++) { if ($i == "-isystem" || $i == "-I") print $(i + 1); else if ($i ~ /^-I./) print substr($i, 3) } }')
layering() {
    local allowed='^/usr/|^(hal/[^/]+\.h|wire/|firmware/|build/lcm_c/)' d
    for d in $lcm_dirs; do allowed="$allowed|^$(realpath -m "$d")/"; done
    cc $ctrl_flags -M "$1" 2>&1 | tr ' \\' '\n\n' | grep -E '\.h$' \
        | while read -r h; do case $h in /*) realpath -m "$h" ;; *) realpath -m --relative-to=. "$h" ;; esac; done \
        | grep -vE "$allowed" | sort -u
}
for f in $(ls firmware/*/*.c | grep -v '^firmware/apps/'); do
    w=$(layering "$f")
    if [ -n "$w" ]; then bad "$f reaches outside hal/ and firmware/: $w"; else ok; fi
done

# Descriptor tables cannot lie: a PARAM_FIELD whose type differs from its
# field's does not compile; the right type does.
ptest="$out/param_probe.c"
param_probe() {
    printf '#include "common/param.h"\ntypedef struct { int16_t a; float b; } p_t;\nconst param_desc_t probe_d[] = { { .key = "a", PARAM_FIELD(p_t, a, %s) }, PARAM_END };\n' "$1" > "$ptest"
    cc $ctrl_flags -Werror -c "$ptest" -o "$out/param_probe.o" 2>/dev/null
}
if param_probe int16_t; then ok; else bad "a right PARAM_FIELD does not compile"; fi
for wrong in uint16_t uint32_t float; do
    if param_probe "$wrong"; then bad "PARAM_FIELD(.., int16_t field, $wrong) compiled"; else ok; fi
done

# The checker must catch what it looks for.
probe="$out/probe.c"
printf '#include <stdlib.h>\nint probe(void);\nint probe(void) { static int count; char *p = malloc(4); free(p); return ++count; }\n' > "$probe"
cc -std=c99 -O0 -c "$probe" -o "$out/probe.o"
if [ -n "$(writable "$out/probe.o")" ]; then ok; else bad "checker missed a mutable static"; fi
if [ -n "$(allocates "$out/probe.o")" ]; then ok; else bad "checker missed malloc"; fi
mkdir -p "$out/firmware_probe"
printf '#include "../../platforms/epuck1/hal/hal_epuck.h"\nint probe2(void);\nint probe2(void) { return 0; }\n' > "$out/firmware_probe/probe.c"
if [ -n "$(layering "$out/firmware_probe/probe.c")" ]; then ok; else bad "checker missed a controller including an e-puck header"; fi

echo "firmware hygiene: $(echo $srcs | wc -w) sources and $(echo $apps | wc -w) images, host and avr-gcc"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
