#!/usr/bin/env bash
# timed.sh NAME COMMAND... - runs one test group and says how long it took:
# "== NAME: passed in 12.3 s" (or "failed"), with the command's status.
name=$1
shift
start=$(date +%s.%N)
"$@"
rc=$?
end=$(date +%s.%N)
secs=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f", b - a }')
if [ "$rc" -eq 0 ]; then
    echo "== $name: passed in $secs s"
else
    echo "== $name: FAILED (status $rc) after $secs s"
fi
exit "$rc"
