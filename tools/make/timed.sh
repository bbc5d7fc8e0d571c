#!/usr/bin/env bash
# timed.sh [-j N] [-t TIMES] COMMAND... -- GROUP... - runs each test group as
# `COMMAND... GROUP` (a make target), N at a time, the longest first by the
# times of the last run that passed (TIMES: "GROUP SECONDS" lines, rewritten
# then; for a group it lacks, tools/make/test_times.txt, a run's times kept
# in the repository; a group in neither goes first).  Each group's output
# is kept together and shown when it ends (as it comes with -j 1), under
# "== GROUP: passed in S s" (or FAILED); then every group's time and the
# wall time.  Once a group fails, no other starts and the status is 1.
set -u
jobs=1 times=/dev/null
while getopts "j:t:" o; do
    case $o in j) jobs=$OPTARG ;; t) times=$OPTARG ;; *) exit 2 ;; esac
done
shift $((OPTIND - 1))
cmd=()
while [ $# -gt 0 ] && [ "$1" != -- ]; do cmd+=("$1"); shift; done
shift
logs=$(mktemp -d "${TMPDIR:-/tmp}/test_groups.XXXXXX") || exit 1
trap 'rm -rf "$logs"' EXIT

i=0
mapfile -t order < <(for g in "$@"; do
    s=$(awk -v g="$g" '$1 == g { print $2; exit }' "$times" "$(dirname "$0")/test_times.txt" 2>/dev/null)
    echo "${s:-1e9} $((i++)) $g"
done | sort -k1,1gr -k2,2n | cut -d' ' -f3)

now() { date +%s.%N; }
secs() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.1f", b - a }'; }
start=$(now)
declare -A pid_of took
running=0 failed=0 next=0
while [ $running -gt 0 ] || { [ $failed -eq 0 ] && [ $next -lt ${#order[@]} ]; }; do
    while [ $failed -eq 0 ] && [ $next -lt ${#order[@]} ] && [ $running -lt "$jobs" ]; do
        g=${order[$next]}
        next=$((next + 1))
        echo "== $g: started"
        # One at a time, the output is shown as it comes.
        ( t0=$(now); if [ "$jobs" -eq 1 ]; then "${cmd[@]}" "$g"; else "${cmd[@]}" "$g" >"$logs/$g.log" 2>&1; fi
          echo "$? $(secs "$t0" "$(now)")" >"$logs/$g.done" ) &
        pid_of[$g]=$!
        running=$((running + 1))
    done
    wait -n
    for g in "${!pid_of[@]}"; do
        [ -f "$logs/$g.done" ] || continue
        wait "${pid_of[$g]}"
        unset "pid_of[$g]"
        running=$((running - 1))
        read -r rc s <"$logs/$g.done"
        [ "$jobs" -eq 1 ] || cat "$logs/$g.log"
        if [ "$rc" -eq 0 ]; then
            took[$g]=$s
            echo "== $g: passed in $s s"
        else
            took[$g]="$s FAILED"
            failed=1
            echo "== $g: FAILED (status $rc) after $s s"
        fi
    done
done
echo "== test groups, $jobs at a time: $(secs "$start" "$(now)") s in all"
for g in "${order[@]}"; do
    read -r v what <<<"${took[$g]:-}"
    if [ -n "$v" ]; then printf '   %-20s %7s s  %s\n' "$g" "$v" "${what:-passed}"; else printf '   %-20s not run\n' "$g"; fi
done
[ $failed -eq 0 ] || exit 1
if [ "$times" != /dev/null ]; then
    { for g in "${order[@]}"; do echo "$g ${took[$g]}"; done
      if [ -f "$times" ]; then     # none on a fresh clone's first run
          awk -v run=" ${order[*]} " 'index(run, " " $1 " ") == 0' "$times"
      fi; } >"$times.$$" &&
        mv "$times.$$" "$times"      # and the times of the groups not run now
fi
