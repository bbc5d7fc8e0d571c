#!/usr/bin/env bash
# spy_display.sh - `make spy` without a display says so in one line, and
# how to get one, instead of Java's HeadlessException stack trace (which it
# printed after building the jar).  (Under a second.)
set -u
cd "$(dirname "$0")/../.."
pass=0 fail=0
check() { if [ "$2" = "$3" ]; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL: $1: got '$2', want '$3'"; fi; }
out=$(env -u DISPLAY -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make --no-print-directory -s spy LCM_URL=memq:// 2>&1)
rc=$?
check "exit status" "$([ "$rc" -ne 0 ] && echo non-zero || echo 0)" non-zero
want="make spy: lcm-spy opens a window and needs a display, but DISPLAY is not set"
check "first line" "$(head -n 1 <<<"$out" | cut -c1-${#want})" "$want"
check "says how" "$(grep -c 'xvfb-run make spy' <<<"$out")" 1
check "no Java trace" "$(grep -cE 'Exception|^[[:space:]]+at ' <<<"$out")" 0
# Besides our line, only make's own (its error line; run from another make,
# its level and directory lines).
check "lines besides make's" "$(grep -vEc '^make(\[[0-9]+\])?: (\*\*\*|Entering|Leaving)' <<<"$out")" 1
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
