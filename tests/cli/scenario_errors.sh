#!/usr/bin/env bash
# scenario_errors.sh - every class of scenario error makes swarmsim exit 2,
# print "swarmsim: FILE:LINE: key.path: message" (or "swarmsim: --set ...")
# on stderr, and write nothing to the --out folder.
#
# usage (from the repository root): bash tests/cli/scenario_errors.sh build/swarmsim
set -u
if [ $# -ne 1 ]; then
    echo "usage: $0 path/to/swarmsim" >&2
    exit 2
fi
sim=$1
case $sim in /*) ;; *) sim="$PWD/$sim" ;; esac
cd "$(dirname "$0")/../.." || exit 1
if [ ! -x "$sim" ]; then
    echo "scenario_errors.sh: '$sim' is not an executable (build it with make)" >&2
    exit 1
fi
tmp=$(mktemp -d "${TMPDIR:-/tmp}/scenario_errors.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT
d=tests/data/scenarios
pass=0 fail=0 n=0

# expect_error NAME EXPECTED-STDERR-TEXT SWARMSIM-ARGS...
# Runs swarmsim with the args and --out in a fresh path; checks exit 2, the
# text on stderr, and that the --out path was not created (or is empty).
expect_error() {
    local name=$1 want=$2 out rc why=""
    shift 2
    n=$((n + 1))
    out="$tmp/out$n"
    "$sim" "$@" --out "$out" >"$tmp/stdout" 2>"$tmp/stderr"
    rc=$?
    if [ "$rc" -ne 2 ]; then
        why="exit status $rc, expected 2"
    elif ! grep -qF -- "$want" "$tmp/stderr"; then
        why="stderr lacks: $want"
    elif [ -e "$out" ] && [ -n "$(ls -A "$out" 2>/dev/null)" ]; then
        why="files were written to the --out folder: $(ls -A "$out" | head -5 | tr '\n' ' ')"
    fi
    if [ -z "$why" ]; then
        pass=$((pass + 1))
    else
        fail=$((fail + 1))
        echo "FAIL: $name: $why"
        sed 's/^/    stderr: /' "$tmp/stderr" | head -5
    fi
}

# ---- errors in the file: FILE:LINE: key.path: message
expect_error "YAML syntax error" \
    "swarmsim: $d/syntax_error.yaml:6: YAML syntax error: " \
    "$d/syntax_error.yaml"
expect_error "unknown key with a suggestion" \
    "swarmsim: $d/unknown_key.yaml:5: robots[0].cuont: unknown key 'cuont' (did you mean 'count'?)" \
    "$d/unknown_key.yaml"
expect_error "integer expected" \
    "swarmsim: $d/wrong_type_int.yaml:3: robots[0].count: expected an integer, got '2.5'" \
    "$d/wrong_type_int.yaml"
expect_error "number expected" \
    "swarmsim: $d/wrong_type_number.yaml:3: arena.width: expected a number, got 'wide'" \
    "$d/wrong_type_number.yaml"
expect_error "boolean expected" \
    "swarmsim: $d/wrong_type_bool.yaml:4: robots[0].moves: expected true/false, got 'yes'" \
    "$d/wrong_type_bool.yaml"
expect_error "mapping expected" \
    "swarmsim: $d/wrong_type_mapping.yaml:2: arena: expected a mapping, got '4'" \
    "$d/wrong_type_mapping.yaml"
expect_error "out of range" \
    "swarmsim: $d/out_of_range.yaml:3: robots[0].count: 200000 is out of range [0, 100000]" \
    "$d/out_of_range.yaml"
expect_error "bad enum value" \
    "swarmsim: $d/bad_enum.yaml:5: robots[0].placement.shape: expected one of rectangle|circle|ring|grid|poses, got 'spiral'" \
    "$d/bad_enum.yaml"
expect_error "duplicate key" \
    "swarmsim: $d/duplicate_key.yaml:4: robots[0].count: duplicate key 'count' (first on line 3)" \
    "$d/duplicate_key.yaml"
expect_error "cylinder without a radius" \
    "swarmsim: $d/cylinder_no_radius.yaml:4: objects[1].radius: a cylinder needs radius > 0" \
    "$d/cylinder_no_radius.yaml"
expect_error "object outside the arena" \
    "swarmsim: $d/object_outside.yaml:4: objects[0]: the cylinder reaches outside the arena" \
    "$d/object_outside.yaml"
expect_error "unknown controller" \
    "swarmsim: $d/bad_controller.yaml:4: robots[0].controller: unknown controller 'levy_walk' (valid: calib, random_walk" \
    "$d/bad_controller.yaml"
expect_error "controller parameter out of range" \
    "swarmsim: $d/bad_controller_param.yaml:5: robots[0].params.speed_steps_s: 5000 is out of range [0, 1000]" \
    "$d/bad_controller_param.yaml"
expect_error "controller needs more IR payload bits" \
    "swarmsim: $d/ircom_too_narrow.yaml:3: robots[0].controller: controller 'forager' sends 16-bit IR messages but ircom.payload_bits is 8" \
    "$d/ircom_too_narrow.yaml"
expect_error "a task's own check" \
    "swarmsim: $d/task_check.yaml:7: foraging.information: 'beacon' needs one robot running nest_beacon" \
    "$d/task_check.yaml"
expect_error "the format before robot groups" \
    "swarmsim: $d/old_syntax.yaml:2: controller: unknown key 'controller': robots are groups now" \
    "$d/old_syntax.yaml"

# ---- too many objects (generated: 4097 entries, the last on line 4098)
{
    echo "objects:"
    for ((i = 0; i < 4097; i++)); do echo "  - { x: 0, y: 0, radius: 0.01 }"; done
} >"$tmp/many.yaml"
expect_error "too many objects" \
    "swarmsim: $tmp/many.yaml:4098: objects[4096]: too many objects (at most 4096)" \
    "$tmp/many.yaml"

# ---- a file that is not there
expect_error "missing file" \
    "swarmsim: $tmp/nope.yaml: cannot open: No such file or directory" \
    "$tmp/nope.yaml"

# ---- bad --set overrides on a valid file: --set TEXT: key.path: message
ok=$d/valid_small.yaml
expect_error "--set: integer expected" \
    "swarmsim: --set robots.0.count=abc: robots[0].count: expected an integer, got 'abc'" \
    "$ok" --set robots.0.count=abc
expect_error "--set: unknown key" \
    "swarmsim: --set robots.0.cuont=5: robots[0].cuont: unknown key 'cuont' (did you mean 'count'?)" \
    "$ok" --set robots.0.cuont=5
expect_error "--set: unknown controller parameter" \
    "swarmsim: --set robots.0.params.speed=3: robots[0].params.speed: unknown key 'speed'" \
    "$ok" --set robots.0.params.speed=3
expect_error "--set: a group past the end" \
    "swarmsim: --set robots.5.count=3: robots[5]: index out of range (the sequence has 1 entries)" \
    "$ok" --set robots.5.count=3
expect_error "--set: out of range" \
    "swarmsim: --set ircom.loss=2: ircom.loss: 2 is out of range [0, 1]" \
    "$ok" --set ircom.loss=2
expect_error "--set: sequence index out of range" \
    "swarmsim: --set objects.7.x=1: objects[7]: index out of range (the sequence has 2 entries)" \
    "$ok" --set objects.7.x=1
expect_error "--set: without '='" \
    "swarmsim: --set robots.0.count: expected key.path=value" \
    "$ok" --set robots.0.count
expect_error "--set: malformed key path" \
    "swarmsim: --set robots..count=3: malformed key path 'robots..count'" \
    "$ok" --set robots..count=3
expect_error "--set: a later override replaces an earlier one" \
    "swarmsim: --set robots.0.count=1.5: robots[0].count: expected an integer, got '1.5'" \
    "$ok" --set robots.0.count=3 --set robots.0.count=1.5

# ---- meaningless setups
: >"$tmp/empty.yaml"
expect_error "an empty scenario file" \
    "swarmsim: $tmp/empty.yaml: empty scenario: it sets nothing" \
    "$tmp/empty.yaml"
expect_error "a forager without its task" \
    "swarmsim: $d/forager_without_task.yaml:5: robots[0].controller: controller 'forager' needs the foraging task" \
    "$d/forager_without_task.yaml"

# ---- the one seed range [0, 2^53 - 1], for --seed and every repetition's seed
expect_error "--seed past the seed range" \
    "swarmsim: --seed: '9007199254740992' is not an integer in [0, 9007199254740991]" \
    "$ok" --seed 9007199254740992
expect_error "repetitions past the seed range" \
    "swarmsim: seeds 9007199254740990 + 3 repetitions pass the seed range [0, 9007199254740991]" \
    "$ok" --seed 9007199254740990 --reps 3

# ---- the memory a run needs is estimated before anything is allocated:
# 16 groups of 100,000 robots (4 GB) are refused, at the robots' line; a
# larger memory_limit_mb lets them through (--check only: it allocates
# nothing), and --check says what a run needs.
{ echo "arena: {width: 400, height: 400}"; echo "robots:";
  for g in $(seq 0 15); do echo "  - {name: g$g, count: 100000, controller: random_walk}"; done; } >"$tmp/huge.yaml"
expect_error "a run past memory_limit_mb" \
    "swarmsim: $tmp/huge.yaml:3: robots: a run of this scenario needs about 4.1 GB (1600000 robots at about 2.6 kB each), more than memory_limit_mb 2048" \
    "$tmp/huge.yaml" --check
n=$((n + 1))
if "$sim" "$tmp/huge.yaml" --check --set memory_limit_mb=6000 >"$tmp/stdout" 2>&1 \
   && grep -qF "huge.yaml: ok (a run needs about 4.1 GB)" "$tmp/stdout"; then
    pass=$((pass + 1))
else
    echo "FAIL: --check with a larger memory_limit_mb: $(cat "$tmp/stdout")"; fail=$((fail + 1))
fi

# ---- --check validates and runs nothing: a bad override fails, a good one
# exits 0 without creating the --out folder.
expect_error "--check: a bad override" \
    "swarmsim: --set robots.0.count=1.5: robots[0].count: expected an integer, got '1.5'" \
    "$ok" --check --set robots.0.count=1.5
n=$((n + 1))
if "$sim" "$ok" --check --seed 9007199254740989 --reps 3 --out "$tmp/check_ok" >"$tmp/stdout" 2>"$tmp/stderr" \
   && [ ! -e "$tmp/check_ok" ] && grep -qF ": ok" "$tmp/stdout"; then
    pass=$((pass + 1))
else
    echo "FAIL: --check on a valid scenario: exit status, output or an --out folder"; fail=$((fail + 1))
fi

# --help documents what the errors point to: every controller with its
# policies, every task, and the keys of each.
n=$((n + 1))
if ! "$sim" --help >"$tmp/help" 2>&1; then
    echo "FAIL: --help: non-zero exit"; fail=$((fail + 1))
else
    missing=""
    for want in "forager " "policies (\`policy:\`): drtm (default), artm, frtm" "phototaxis " \
                "gather " "robots[].params" "foraging.food_count" "gather.goal.x"; do
        grep -qF -- "$want" "$tmp/help" || missing="$missing '$want'"
    done
    if [ -n "$missing" ]; then
        echo "FAIL: --help lacks:$missing"; fail=$((fail + 1))
    else
        pass=$((pass + 1))
    fi
fi

echo "$pass passed, $fail failed"
if [ "$fail" -ne 0 ]; then
    echo "scenario_errors.sh: $fail of $n checks failed" >&2
    exit 1
fi
