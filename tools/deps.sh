#!/usr/bin/env bash
# deps.sh - find or install what the build needs, then print build/config.mk
# on stdout.  Called by the Makefile when build/config.mk is missing or older
# than this script; a second run finds everything and installs nothing.
#
# Debian packages are installed with apt-get when we are root; the pinned
# wheels of tools/requirements.txt go into the project-local .venv.  When
# something cannot be installed, it says what is missing and how to get it,
# and exits 1.
set -euo pipefail
cd "$(dirname "$0")/.."
VENV=${VENV:-.venv}
say() { echo "deps: $*" >&2; }
# A line per step with the time it took: "deps: [2/3] ... (2 min 41 s)".
STEPS=3
step_start() { step_t0=$SECONDS; step_n=$1; shift; say "[$step_n/$STEPS] $*"; }
step_done() { local s=$((SECONDS - step_t0)); say "[$step_n/$STEPS] $* ($( ((s >= 60)) && echo "$((s / 60)) min $((s % 60)) s" || echo "$s s"))"; }

# package-name : check command (true when present)
declare -a missing=()
need() { # need DEBIAN_PACKAGE CHECK...
    local pkg=$1; shift
    if ! "$@" >/dev/null 2>&1; then missing+=("$pkg"); fi
}
pc() { pkg-config --exists "$1"; }
hdr() { printf '#include <%s>\n' "$1" | cc -E -x c - >/dev/null; }

check_all() {
    missing=()
    need pkg-config       command -v pkg-config
    need libcmocka-dev    pc cmocka
    need libyaml-dev      pc yaml-0.1
    need libpng-dev       pc libpng
    need libosmesa6-dev   hdr GL/osmesa.h
    need gcc-avr          command -v avr-gcc
    need avr-libc         hdr_avr
    need gcc-arm-none-eabi       command -v arm-none-eabi-gcc
    need libnewlib-arm-none-eabi hdr_arm
    need python3-venv     python3 -c 'import venv, ensurepip'
    need libglib2.0-0     glib_runtime      # liblcm.a (the lcm wheel) calls GLib
    need valgrind         command -v valgrind   # firmware CPU report (callgrind)
    need ffmpeg           command -v ffmpeg     # swarmsim --video (and ffprobe for its tests)
    need libsimavr-dev    simavr_links          # the emulated ATmega2560 of processor-in-the-loop (platforms/pil_avr/emu/)
    need qemu-system-arm  qemu_netduino         # the emulated Cortex-M4F of processor-in-the-loop (platforms/pil_m4/)
    need gdb-multiarch    command -v gdb-multiarch   # the e-puck2's flasher (its programmer is a GDB server) and its test
    # The fuzz harnesses (tests/fuzz/, tools/make/fuzz.mk): clang, its
    # sanitizer and libFuzzer runtime (a separate package named after
    # clang's major version, so it is looked for once clang is there), and
    # llvm-symbolizer for readable crash stacks.
    need clang            command -v clang
    need llvm             command -v llvm-symbolizer
    if command -v clang >/dev/null 2>&1; then
        need "$(clang_rt_package)" libfuzzer_links
    fi
}
clang_major() { clang -dumpversion | cut -d. -f1; }
# Debian 12 splits the runtime out as libclang-rt-N-dev; older releases keep
# it in libclang-common-N-dev.
clang_rt_package() {
    local v; v=$(clang_major)
    if apt-cache show "libclang-rt-$v-dev" >/dev/null 2>&1; then echo "libclang-rt-$v-dev"
    else echo "libclang-common-$v-dev"; fi
}
libfuzzer_links() {
    printf '#include <stddef.h>\n#include <stdint.h>\nint LLVMFuzzerTestOneInput(const uint8_t *d, size_t n) { (void)d; (void)n; return 0; }\n' \
        | clang -fsanitize=fuzzer,address,undefined -x c - -o /dev/null
}
glib_runtime() { { ldconfig -p 2>/dev/null || /sbin/ldconfig -p; } | grep -q 'libglib-2.0.so.0'; }
simavr_links() { printf '#include <simavr/sim_avr.h>\nint main(void) { return avr_make_mcu_by_name("atmega2560") == 0; }\n' | cc -x c - -lsimavr -o /dev/null; }
qemu_netduino() { qemu-system-arm -machine help | grep -q '^netduinoplus2 '; }
hdr_avr() { printf '#include <stdint.h>\n' | avr-gcc -mmcu=atmega128 -E -x c - >/dev/null; }
hdr_arm() { printf '#include <string.h>\n' | arm-none-eabi-gcc -mcpu=cortex-m4 -E -x c - >/dev/null; }

# Two rounds: clang's runtime package is known only once clang is installed.
step_start 1 "Debian packages: checking"
check_all
for _ in 1 2; do
    [ ${#missing[@]} -gt 0 ] && [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null || break
    say "installing Debian packages: ${missing[*]}"
    export DEBIAN_FRONTEND=noninteractive
    if ! apt-get install -y --no-install-recommends "${missing[@]}" >&2; then
        apt-get update >&2 && apt-get install -y --no-install-recommends "${missing[@]}" >&2 || true
    fi
    check_all
done
if [ ${#missing[@]} -gt 0 ]; then
    say "missing Debian packages: ${missing[*]}"
    say "install them with:  sudo apt-get install ${missing[*]}"
    exit 1
fi
step_done "Debian packages: all there"

# Project-local virtualenv with the pinned wheels.
stamp="$VENV/.requirements-$(sha1sum tools/requirements.txt | cut -c1-12)"
if [ ! -f "$stamp" ]; then
    step_start 2 "$VENV: installing the $(grep -c '^[A-Za-z]' tools/requirements.txt) pinned wheels of tools/requirements.txt (pip's own lines follow; a few minutes the first time)"
    python3 -m venv "$VENV" >&2
    # pip's progress: a line per wheel, and its progress bars on a terminal.
    if ! "$VENV/bin/pip" install --disable-pip-version-check --progress-bar on -r tools/requirements.txt >&2; then
        say "could not install the wheels of tools/requirements.txt (lcm, pyb2d3, numpy, scipy, matplotlib, ruff, ...)"
        say "they come from PyPI: check the network, or install a system Box2D >= 3.1 and LCM 1.5.3"
        exit 1
    fi
    touch "$stamp"
    step_done "$VENV: the pinned wheels are installed"
else
    step_start 2 "$VENV: the pinned wheels are installed already"
fi
step_start 3 "Box2D and LCM: looking"
SITE=$("$VENV/bin/python" -c 'import sysconfig; print(sysconfig.get_paths()["platlib"])')

# Box2D 3.1.x (the tested range: the golden hashes are pinned on 3.1.1): a
# system install if pkg-config knows one in that range, else the wheel's.
if pkg-config --atleast-version=3.1 box2d 2>/dev/null && ! pkg-config --atleast-version=3.2 box2d 2>/dev/null; then
    BOX2D_CFLAGS=$(pkg-config --cflags box2d); BOX2D_LIBS=$(pkg-config --libs box2d)
    say "using the system Box2D $(pkg-config --modversion box2d)"
else
    if pkg-config --exists box2d 2>/dev/null; then
        say "ignoring the system Box2D $(pkg-config --modversion box2d): outside the tested 3.1.x; using pyb2d3's 3.1.1"
    fi
    [ -f "$SITE/lib64/libbox2d.a" ] || { say "pyb2d3 wheel has no lib64/libbox2d.a in $SITE"; exit 1; }
    BOX2D_CFLAGS="-isystem $SITE/include"; BOX2D_LIBS="$SITE/lib64/libbox2d.a"
fi
# LCM 1.5.3: the wheel's (a system one is used if pkg-config finds lcm >= 1.5).
if pkg-config --atleast-version=1.5 lcm 2>/dev/null && command -v lcm-gen >/dev/null; then
    LCM_CFLAGS=$(pkg-config --cflags lcm); LCM_LIBS=$(pkg-config --libs lcm); LCM_GEN=$(command -v lcm-gen)
else
    LCM_CFLAGS="-isystem $SITE/include"; LCM_LIBS="$SITE/lib/liblcm.a $(pkg-config --libs glib-2.0 2>/dev/null || true)"
    LCM_GEN="$SITE/bin/lcm-gen"
fi

step_done "Box2D and LCM: found"
cat <<MK
# Generated by tools/deps.sh; delete it to look again.
VENV := $VENV
PYTHON := $VENV/bin/python
BOX2D_CFLAGS := $BOX2D_CFLAGS
BOX2D_LIBS := $BOX2D_LIBS
LCM_CFLAGS := $LCM_CFLAGS
LCM_LIBS := $LCM_LIBS
LCM_GEN := $LCM_GEN
CMOCKA_CFLAGS := $(pkg-config --cflags cmocka)
CMOCKA_LIBS := $(pkg-config --libs cmocka)
YAML_LIBS := $(pkg-config --libs yaml-0.1)
PNG_CFLAGS := $(pkg-config --cflags libpng)
PNG_LIBS := $(pkg-config --libs libpng)
GL_LIBS := -lOSMesa
FUZZ_CC := clang
MK
