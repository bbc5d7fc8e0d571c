#!/usr/bin/env bash
# hygiene.sh - checks the firmware rules on the compiled objects:
#  1. every source of the robot's layers compiles warning-free as C99, each
#     with only the include folders its layer may use (below), so an
#     include that points up the layers is a build error: the portable
#     layers on the host and with avr-gcc (16-bit int and pointers, 32-bit
#     double: the data model of XC16 on the dsPIC), a platform's with the
#     compilers its platform.py names (HYGIENE_COMPILERS);
#  2. no object has writable static data (.data/.bss non-empty or data
#     symbols): controllers keep all state in their structs;
#  3. nothing calls malloc/calloc/realloc/free;
#  4. no conditional compilation in controllers except include guards;
#  5. layering: `cc -M` lists every header a source (or a header) really
#     reads, relative includes too, and each must be in its layer's folders;
#  6. parameter descriptors whose type does not match their field do not
#     compile.
# The layers, bottom up, and what each may include (besides the C library):
#   hal       hal/ (the contract and its platform-neutral helpers)
#   wire      + wire/ (the wire protocols: telemetry framing, the host link)
#   firmware  + firmware/ and lcm-gen's headers (the controllers, the
#             robot's own telemetry)
#   P-hal     hal/, wire/ + platforms/P/hal/ (platform P's HAL: no controller)
#   P-run     everything above + platforms/P/run/ (P's run loop)
#   P-image   P-run + the generated mains (build/firmware/gen/P/)
# A platform's HAL obeys rules 1-3 too: its state is the caller's struct
# hal.  The images' mains (generated from platforms/P/images.list) compile
# under rule 1 and call no allocator; their static variables are the one
# documented exception (no heap on the robot, main never returns): only the
# robot's struct hal (app_hal), the controller (app_*) and the camera frames
# (camera_frames) may be writable statics there; app_* includes the
# telemetry sender and its buffers (app_telemetry).
# The checker is itself checked on probes it must catch.
set -u
cd "$(dirname "$0")/../.."
out=build/fw
gen=${FW_GEN:-build/firmware/gen}
lcm_c=${LCM_C_DIR:-build/lcm_c}
mkdir -p "$out"
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }

warn="-std=c99 -pedantic -Wall -Wextra -Werror -Wshadow -Wstrict-prototypes -Wmissing-prototypes"
lcm_flags="-I$lcm_c ${LCM_CFLAGS:-}"
lcm_dirs=$(echo "${LCM_CFLAGS:-}" | awk '{ for (i = 1; i <= NF; i++) { if ($i == "-isystem" || $i == "-I") print $(i + 1); else if ($i ~ /^-I./) print substr($i, 3) } }')
platforms=$(sed -e 's/#.*//' platforms/platforms.list)

# layer_inc LAYER - its include flags.  layer_allowed LAYER - the folders
# (regular expression) its headers may come from.
layer_inc() {
    local p=${1%%-*}
    case $1 in
        hal) echo "-Ihal" ;;
        wire) echo "-Ihal -Iwire" ;;
        firmware) echo "-Ihal -Iwire -Ifirmware $lcm_flags" ;;
        *-hal) echo "-Ihal -Iwire -Iplatforms/$p/hal" ;;
        *-run) echo "-Ihal -Iwire -Ifirmware -Iplatforms/$p/hal -Iplatforms/$p/run $lcm_flags" ;;
        *-image) echo "-Ihal -Iwire -Ifirmware -Iplatforms/$p/hal -Iplatforms/$p/run -I$gen/$p $lcm_flags" ;;
    esac
}
layer_allowed() {
    local p=${1%%-*} a d
    case $1 in
        hal) a='hal/[^/]+\.h' ;;
        wire) a='hal/[^/]+\.h|wire/' ;;
        firmware) a='hal/[^/]+\.h|wire/|firmware/|build/lcm_c/' ;;
        *-hal) a="hal/[^/]+\\.h|wire/|platforms/$p/hal/" ;;
        *-run) a="hal/[^/]+\\.h|wire/|firmware/|build/lcm_c/|platforms/$p/hal/|platforms/$p/run/" ;;
        *-image) a="hal/[^/]+\\.h|wire/|firmware/|build/lcm_c/|platforms/$p/hal/|platforms/$p/run/|$gen/$p/" ;;
    esac
    a="^/usr/|^($a)"
    case $1 in firmware|*-run|*-image) for d in $lcm_dirs; do a="$a|^$(realpath -m "$d")/"; done ;; esac
    echo "$a"
}
# layering LAYER FILE - prints what FILE (a source or a header) includes
# that its layer may not: a header not found on the layer's include path
# (an upward include by name), or a header read from outside the layer's
# folders (an upward include by relative path).  Nothing when it is clean.
layering() {
    local deps
    if ! deps=$(cc -std=c99 $(layer_inc "$1") -x c -M "$2" 2>&1); then
        echo "$deps" | grep -m1 -E 'fatal error|error:' || echo "does not preprocess"
        return
    fi
    local hs abs rel
    hs=$(echo "$deps" | tr ' \\' '\n\n' | grep -E '\.h$' | sort -u)
    abs=$(echo "$hs" | grep '^/' | grep -v '^/usr/')
    rel=$(echo "$hs" | grep -v '^/')
    { [ -z "$abs" ] || realpath -m $abs; [ -z "$rel" ] || realpath -m --relative-to=. $rel; } \
        | grep -vE "$(layer_allowed "$1")" | sort -u
}

# Writable static data in one object: prints what it finds.
writable() {
    local o=$1
    size -A "$o" | awk '$1 ~ /^\.(data|bss)(\.|$)/ && $2 > 0 { print "section " $1 " has " $2 " bytes" }'
    nm "$o" | awk '$2 ~ /^[dDbBC]$/ { print "writable symbol " $3 }'
}
allocates() { nm -u "$1" | awk '$2 ~ /^(malloc|calloc|realloc|free)$/ { print "calls " $2 }'; }

# Every source and header of the robot's layers, as "LAYER FILE".
units() {
    local f p
    for f in hal/*.c hal/*.h; do echo "hal $f"; done
    for f in wire/*/*.c wire/*/*.h; do echo "wire $f"; done
    for f in firmware/*/*.c firmware/*/*.h; do echo "firmware $f"; done
    for p in $platforms; do
        for f in platforms/$p/hal/*.c platforms/$p/hal/*.h; do [ -e "$f" ] && echo "$p-hal $f"; done
        for f in platforms/$p/run/*.c platforms/$p/run/*.h; do [ -e "$f" ] && echo "$p-run $f"; done
    done
}

# Rules 1-3 on the sources; rule 5 on sources and headers.  A run loop's
# image_main.h is the body of its images' mains (it stops without their
# declaration): it is checked through them.
# compilers LAYER - the compilers a layer's sources must build with, one a
# line: the host's and avr-gcc (16-bit int) for the portable layers; a
# platform's own (platform.py's HYGIENE_COMPILERS) for its HAL, run loop and
# images.  The first one's objects are checked for statics and allocators.
declare -A platform_cc
portable_cc=$'cc -fno-pie -O2\navr-gcc -mmcu=atmega128 -Os'
for p in $platforms; do
    [ -f "platforms/$p/platform.py" ] || continue
    platform_cc[$p]=$(python3 tools/make/images.py platform-value "platforms/$p" HYGIENE_COMPILERS) \
        || bad "platforms/$p/platform.py: no HYGIENE_COMPILERS"
done
compilers() {
    case $1 in
        hal|wire|firmware) echo "$portable_cc" ;;
        *) echo "${platform_cc[${1%%-*}]:-}" ;;
    esac
}
# build LAYER SRC NAME - compiles SRC with each of its layer's compilers
# (rule 1); sets `built` to the first object's path, or to nothing when one
# failed.
build() {
    local k=0 c first="" obj
    built=
    while read -r c; do
        [ -n "$c" ] || continue
        k=$((k + 1))
        obj="$out/cc$k/$3.o"
        mkdir -p "$out/cc$k"
        if ! $c $warn $(layer_inc "$1") -c "$2" -o "$obj"; then
            bad "$2 does not compile warning-free with $c"
            return
        fi
        ok
        [ -n "$first" ] || first=$obj
    done < <(compilers "$1")
    if [ -z "$first" ]; then bad "$2: no compilers for the $1 layer"; return; fi
    built=$first
}

nsrc=0
while read -r layer src; do
    case $src in */run/image_main.h) continue ;; esac
    w=$(layering "$layer" "$src")
    if [ -n "$w" ]; then bad "$src ($layer layer) includes what its layer may not: $w"; else ok; fi
    case $src in *.c) ;; *) continue ;; esac
    nsrc=$((nsrc + 1))
    build "$layer" "$src" "$(echo "${src%.c}" | tr / _)"
    obj=$built
    [ -n "$obj" ] || continue
    w=$(writable "$obj")
    if [ -n "$w" ]; then bad "$src: writable static data: $w"; else ok; fi
    a=$(allocates "$obj")
    if [ -n "$a" ]; then bad "$src: $a"; else ok; fi
done < <(units)

# Images (the generated mains, make firmware-images): warning-free with the
# platform's compilers, within their layer, no allocator, and no writable
# statics but the documented ones.
nimg=0
for p in $platforms; do
    [ -n "$(python3 tools/make/images.py list-file "platforms/$p")" ] || continue
    mains=$(ls "$gen/$p"/*_main.c 2>/dev/null)
    if [ -z "$mains" ]; then bad "$gen/$p has no generated mains: run make firmware-images"; continue; fi
    for src in $mains; do
        nimg=$((nimg + 1))
        w=$(layering "$p-image" "$src")
        if [ -n "$w" ]; then bad "$src ($p-image layer) includes what its layer may not: $w"; else ok; fi
        build "$p-image" "$src" "image_${p}_$(basename "${src%.c}")"
        obj=$built
        [ -n "$obj" ] || continue
        w=$(nm "$obj" | awk '$2 ~ /^[dDbBC]$/ { print $3 }' | grep -vE '^(app_[A-Za-z0-9_]+|camera_frames)(\.[0-9]+)?$')
        if [ -n "$w" ]; then bad "$src: undocumented writable statics: $w"; else ok; fi
        a=$(allocates "$obj")
        if [ -n "$a" ]; then bad "$src: $a"; else ok; fi
    done
done

# Controllers: no #if/#ifdef other than the include guard of a header.
for f in firmware/*/*.[ch]; do
    n=$(grep -cE '^\s*#\s*(if|ifdef|ifndef|elif)\b' "$f")
    guard=0
    case "$f" in *.h) guard=1 ;; esac
    if [ "$n" -gt "$guard" ]; then bad "$f: conditional compilation in a controller"; else ok; fi
done

# Descriptor tables cannot lie: a PARAM_FIELD whose type differs from its
# field's does not compile; the right type does.
ptest="$out/param_probe.c"
param_probe() {
    printf '#include "common/param.h"\ntypedef struct { int16_t a; float b; } p_t;\nconst param_desc_t probe_d[] = { { .key = "a", PARAM_FIELD(p_t, a, %s) }, PARAM_END };\n' "$1" > "$ptest"
    cc -std=c99 $(layer_inc firmware) -Werror -c "$ptest" -o "$out/param_probe.o" 2>/dev/null
}
if param_probe int16_t; then ok; else bad "a right PARAM_FIELD does not compile"; fi
for wrong in uint16_t uint32_t float; do
    if param_probe "$wrong"; then bad "PARAM_FIELD(.., int16_t field, $wrong) compiled"; else ok; fi
done
# PARAM_ARRAY_FIELD likewise: the element type must be the array's, and a
# scalar field is not an array.
array_probe() {
    printf '#include "common/param.h"\ntypedef struct { int16_t a[6]; int16_t s; } p_t;\nconst param_desc_t probe_d[] = { { .key = "a", PARAM_ARRAY_FIELD(p_t, %s, %s) }, PARAM_END };\n' "$1" "$2" > "$ptest"
    cc -std=c99 $(layer_inc firmware) -Wall -Wextra -Werror -c "$ptest" -o "$out/param_probe.o" 2>/dev/null
}
if array_probe a int16_t; then ok; else bad "a right PARAM_ARRAY_FIELD does not compile"; fi
for wrong in "a uint16_t" "a uint8_t" "a float" "s int16_t"; do
    # shellcheck disable=SC2086
    if array_probe $wrong; then bad "PARAM_ARRAY_FIELD($wrong) compiled"; else ok; fi
done

# The checker must catch what it looks for.
probe="$out/probe.c"
printf '#include <stdlib.h>\nint probe(void);\nint probe(void) { static int count; char *p = malloc(4); free(p); return ++count; }\n' > "$probe"
cc -std=c99 -O0 -c "$probe" -o "$out/probe.o"
if [ -n "$(writable "$out/probe.o")" ]; then ok; else bad "checker missed a mutable static"; fi
if [ -n "$(allocates "$out/probe.o")" ]; then ok; else bad "checker missed malloc"; fi
# Layering probes: a file of a layer that includes a header of a layer above
# it, by name (not found on its include path) and by a relative path (found,
# but outside its folders); and a clean one of each, which must pass.  The
# probes sit in build/fw/layer_probe/, so ../../../ is the repository.
pdir="$out/layer_probe"
mkdir -p "$pdir"
layer_probe() {   # LAYER WANT(clean|caught) INCLUDE
    local f="$pdir/probe_$RANDOM.c" w
    printf '#include "%s"\nint layer_probe(void);\nint layer_probe(void) { return 0; }\n' "$3" > "$f"
    w=$(layering "$1" "$f")
    case $2 in
        clean) if [ -z "$w" ]; then ok; else bad "the layering check refused a $1 file including $3: $w"; fi ;;
        caught) if [ -n "$w" ]; then ok; else bad "the layering check missed a $1 file including $3"; fi ;;
    esac
    rm -f "$f"
}
rel=../../../
# Each relative probe must name a real header (else it would be caught for
# not being found, not for where it is).
for h in firmware/common/controller.h platforms/epuck1/hal/hal_epuck.h wire/telemetry/telemetry_frame.h; do
    if [ -f "$h" ]; then ok; else bad "layering probe header $h is not in the repository"; fi
done
layer_probe hal clean hal.h
layer_probe hal caught common/controller.h
layer_probe hal caught telemetry/telemetry_frame.h
layer_probe hal caught "${rel}firmware/common/controller.h"
layer_probe hal caught "${rel}wire/telemetry/telemetry_frame.h"
layer_probe wire clean hal.h
layer_probe wire caught common/controller.h
layer_probe wire caught hal_epuck.h
layer_probe wire caught "${rel}firmware/common/controller.h"
layer_probe firmware clean telemetry/telemetry_tx.h
layer_probe firmware caught hal_epuck.h
layer_probe firmware caught "${rel}platforms/epuck1/hal/hal_epuck.h"
layer_probe epuck1-hal clean telemetry/telemetry_rx.h
layer_probe epuck1-hal caught foraging/forager.h
layer_probe epuck1-hal caught telemetry/robot_telemetry.h
layer_probe epuck1-hal caught "${rel}firmware/common/controller.h"
layer_probe epuck1-run clean foraging/forager.h
layer_probe epuck1-run caught "${rel}sim_host/core/sim.h"

echo "firmware hygiene: $nsrc sources and $nimg images, each layer with its compilers and only its include path"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
