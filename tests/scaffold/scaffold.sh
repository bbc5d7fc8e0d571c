#!/usr/bin/env bash
# scaffold.sh - `make new-controller` and `make new-task` give sources that
# build and run: tools/scaffold.py writes a controller foo and a task bar
# into a copy of firmware/ and sim_host/; they compile with the project's
# flags (-Werror), the registry (tools/make/registry.sh over the copy) lists
# them, the simulator linked with them lists them in --help and runs both
# scenarios; a name already taken, or not an identifier, is refused (exit
# 2) with nothing written.  Run by `make scaffold-tests` (CC, FW_CFLAGS,
# SIM_CFLAGS, LDLIBS, BUILD, PYTHON from the Makefile).  (A few seconds.)
set -u
cd "$(dirname "$0")/../.."
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $1"; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
repo=$tmp/repo
mkdir -p "$repo/tools/make" "$tmp/obj" "$tmp/gen"
cp -r firmware sim_host "$repo/"
cp tools/make/registry.sh "$repo/tools/make/"

scaffold() { "$PYTHON" tools/scaffold.py "$@" --root "$repo"; }
files() { (cd "$repo" && find . -type f | LC_ALL=C sort); }

if scaffold controller foo > "$tmp/c.out"; then ok; else bad "scaffold controller foo: exit $?"; fi
if scaffold task bar > "$tmp/t.out"; then ok; else bad "scaffold task bar: exit $?"; fi
for f in firmware/foo/foo.h firmware/foo/foo.c firmware/foo/foo_def.c sim_host/scenarios/foo.yaml \
         sim_host/tasks/bar/bar.h sim_host/tasks/bar/bar.c sim_host/scenarios/bar.yaml; do
    if [ -f "$repo/$f" ]; then ok; else bad "scaffold wrote no $f"; fi
done
if grep -q phototaxis "$repo"/firmware/foo/*; then bad "firmware/foo/ still names phototaxis"; else ok; fi
if grep -qi gather "$repo"/sim_host/tasks/bar/*; then bad "sim_host/tasks/bar/ still names gather"; else ok; fi

# Refusals: nothing written.
before=$(files)
for args in "controller foo" "task bar" "controller phototaxis" "task gather" "controller Foo" \
            "controller 9lives" "task int" "controller random_walk"; do
    # shellcheck disable=SC2086
    scaffold $args > /dev/null 2> "$tmp/err"
    rc=$?
    if [ "$rc" -eq 2 ] && grep -q "nothing written" "$tmp/err"; then ok
    else bad "scaffold $args: exit $rc, $(cat "$tmp/err")"; fi
done
if [ "$(files)" = "$before" ]; then ok; else bad "a refused scaffold wrote files"; fi

# Compile the new sources as the Makefile does, the registry over the copy,
# and link them with the simulator's library.
compile() {   # flags source
    local o=$tmp/obj/$(basename "${2%.c}").o
    # shellcheck disable=SC2086
    if $CC $1 -c "$2" -o "$o" 2> "$tmp/cc.err"; then ok; else bad "$2 does not compile: $(head -5 "$tmp/cc.err")"; fi
}
for c in "$repo"/firmware/foo/*.c; do compile "-I$repo/firmware $FW_CFLAGS" "$c"; done
compile "-I$repo/sim_host $SIM_CFLAGS" "$repo/sim_host/tasks/bar/bar.c"
if REGISTRY_ROOT=$repo bash "$repo/tools/make/registry.sh" "$tmp/gen/registry_list.h"; then ok; else bad "registry.sh over the copy"; fi
compile "-I$tmp/gen $SIM_CFLAGS" sim_host/registry.c
# shellcheck disable=SC2086
if $CC -o "$tmp/swarmsim" "$BUILD/obj/sim_host/main.o" "$tmp"/obj/*.o "$BUILD/libswarm.a" $LDLIBS 2> "$tmp/ld.err"; then ok
else bad "the simulator does not link with them: $(head -5 "$tmp/ld.err")"; fi

if [ -x "$tmp/swarmsim" ]; then
    help=$("$tmp/swarmsim" --help)
    if grep -qE '^  foo +example' <<<"$help"; then ok; else bad "--help lists no controller foo"; fi
    if grep -qE '^  bar +example' <<<"$help"; then ok; else bad "--help lists no task bar"; fi
    for s in foo bar; do
        if "$tmp/swarmsim" "$repo/sim_host/scenarios/$s.yaml" --steps 200 --lcm off --quiet --out "$tmp/out_$s"; then ok
        else bad "sim_host/scenarios/$s.yaml does not run"; fi
        if [ -f "$tmp/out_$s/run_1/summary.json" ]; then ok; else bad "$s's run wrote no summary"; fi
    done
    if grep -q '"controller": "foo"' "$tmp/out_foo/run_1/summary.json" 2>/dev/null; then ok; else bad "foo.yaml's robots do not run foo"; fi
    if grep -q '"bar"' "$tmp/out_bar/run_1/summary.json" 2>/dev/null; then ok; else bad "bar.yaml does not run the task bar"; fi
fi
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
