#!/usr/bin/env bash
# test_driver.sh - make test's group driver (tools/make/timed.sh) on a
# throw-away Makefile: a fresh clone's first run (no times file yet) passes
# and writes the times; the longest group by the last times starts first; a
# failed group gives status 1, keeps its output, starts no other group and
# leaves the times as they were; a later run keeps the times of groups it did
# not run.  Usage: test_driver.sh [SWARMSIM] (not used).  (Under a second.)
set -u
cd "$(dirname "$0")/../.."
driver=$PWD/tools/make/timed.sh
pass=0 fail=0
check() { if eval "$2"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL: $1"; fi; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
printf 'a:\n\t@echo out-a\nb:\n\t@echo out-b\nbad:\n\t@echo out-bad; exit 3\n' > "$tmp/Makefile"
run() { TMPDIR=$tmp bash "$driver" "$@" > "$tmp/out" 2>&1; echo $? > "$tmp/rc"; }

run -j 2 -t "$tmp/times" -- make -s -C "$tmp" -- a b
check "a first run without a times file passes" "[ \$(cat '$tmp/rc') -eq 0 ]"
check "and writes every group's time" "grep -q '^a [0-9.]*$' '$tmp/times' && grep -q '^b [0-9.]*$' '$tmp/times'"
check "each group's output under its name" "grep -q '^out-a$' '$tmp/out' && grep -q '== b: passed in' '$tmp/out'"

printf 'a 1\nb 9\n' > "$tmp/times"
run -j 1 -t "$tmp/times" -- make -s -C "$tmp" -- a b
check "the longest by the last times starts first" "[ \"\$(grep -m1 'started' '$tmp/out')\" = '== b: started' ]"

printf 'a 1\nb 2\nbad 9\n' > "$tmp/times"
cp "$tmp/times" "$tmp/times.before"
run -j 1 -t "$tmp/times" -- make -s -C "$tmp" -- bad a b
check "a failed group gives status 1" "[ \$(cat '$tmp/rc') -eq 1 ]"
check "its output is kept and it is named" "grep -q '^out-bad$' '$tmp/out' && grep -q '== bad: FAILED (status 2)' '$tmp/out'"
check "no group starts after it" "! grep -q '== a: started' '$tmp/out' && grep -q '^   a  *not run$' '$tmp/out'"
check "the times are left as they were" "cmp -s '$tmp/times' '$tmp/times.before'"

run -j 2 -t "$tmp/times" -- make -s -C "$tmp" -- a
check "a run of some groups keeps the others' times" "grep -q '^bad 9$' '$tmp/times' && grep -q '^b 2$' '$tmp/times' && [ \$(grep -c '^a ' '$tmp/times') -eq 1 ]"
check "no temporary file left" "[ -z \"\$(ls '$tmp' | grep -v '^Makefile$\|^times$\|^times.before$\|^out$\|^rc$')\" ]"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
