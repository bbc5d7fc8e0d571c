#!/usr/bin/env bash
# registry.sh - the simulator's registry comes from the sources
# (tools/make/registry.sh): every controller and task description in the
# repository is in swarmsim --help; in a made-up tree a new description is
# found, a description in another form is an error naming its line, and an
# unchanged list leaves the header untouched.  About 1 s.
#
# usage (from the repository root): bash tests/cli/registry.sh build/swarmsim
set -u
sim=$1
case $sim in /*) ;; *) sim="$PWD/$sim" ;; esac
cd "$(dirname "$0")/../.." || exit 1
gen=$PWD/tools/make/registry.sh
tmp=$(mktemp -d "${TMPDIR:-/tmp}/registry.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0
check() { if [ "$1" = 0 ]; then pass=$((pass + 1)); else echo "FAIL: $2"; fail=$((fail + 1)); fi; }

# Every description in the repository is registered: its name is in --help.
"$sim" --help >"$tmp/help" 2>&1
for f in firmware/*/*_def.c sim_host/tasks/*/*.c; do
    sym=$(sed -nE 's/^const (controller|task)_def_t ([a-z_0-9]+) = \{$/\2/p' "$f")
    [ -n "$sym" ] || continue
    name=$(grep -A3 -E "^const (controller|task)_def_t $sym = \{" "$f" | sed -nE 's/.*\.name = "([a-z_0-9]+)".*/\1/p')
    if [ -z "$name" ]; then    # the controllers name themselves by a macro
        macro=$(grep -A3 -E "^const controller_def_t $sym = \{" "$f" | sed -nE 's/.*\.name = ([A-Z_0-9]+).*/\1/p')
        name=$(grep -rhE "#define $macro \"" firmware | sed -nE 's/.*"([a-z_0-9]+)".*/\1/p')
    fi
    [ -n "$name" ] && grep -qE "^  $name " "$tmp/help"
    check $? "$f: '$name' ($sym) is not in swarmsim --help"
done

# A made-up tree: one controller, one task.
root=$tmp/tree
mkdir -p "$root/firmware/mine" "$root/sim_host/tasks/t"
printf 'const controller_def_t mine_def = {\n};\n' >"$root/firmware/mine/mine_def.c"
printf 'static int helper(const task_def_t *t);\nconst task_def_t t_task = {\n};\n' >"$root/sim_host/tasks/t/t.c"
REGISTRY_ROOT=$root bash "$gen" "$tmp/list.h"
check $? "the generator failed on a good tree"
grep -qF '#define REGISTRY_CONTROLLERS &mine_def,' "$tmp/list.h"
check $? "mine_def is not in the controllers: $(cat "$tmp/list.h")"
grep -qF '#define REGISTRY_TASKS &t_task,' "$tmp/list.h"
check $? "t_task is not in the tasks"

# Unchanged: the header keeps its time stamp.
touch -d '2001-01-01' "$tmp/list.h"
REGISTRY_ROOT=$root bash "$gen" "$tmp/list.h"
[ "$(stat -c %Y "$tmp/list.h")" = "$(date -d '2001-01-01' +%s)" ]
check $? "an unchanged list rewrote the header"

# Another form is an error naming the file and line; the header stays.
printf '/* x */\nstatic const controller_def_t other_def = {\n};\n' >"$root/firmware/mine/other_def.c"
REGISTRY_ROOT=$root bash "$gen" "$tmp/list.h" 2>"$tmp/err"
rc=$?
[ "$rc" -ne 0 ] && grep -qF "firmware/mine/other_def.c:2:static const controller_def_t other_def" "$tmp/err" &&
    ! grep -q other_def "$tmp/list.h"
check $? "a static description: exit $rc, stderr: $(cat "$tmp/err")"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
