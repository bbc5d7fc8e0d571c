#!/usr/bin/env bash
# control.sh - a running simulation steered over LCM (swarmsim --control,
# sim_host/core/control.h): a run paused, stepped and resumed ends with the
# state hash of one nobody touched; its step counter stops while paused and
# moves by exactly N for `step N`; every command is an event of the
# telemetry and a line of summary.json; a moved robot marks the run touched
# (and changes it); a command for a robot that does not exist, a pose
# outside the arena, a step of 0 are refused with a reason and change
# nothing; a command without the run's key is ignored; options that
# cannot work are exit-2 errors.  Each run under control waits (--paused)
# for the commands, which wait for the run's answers: no fixed sleeps.
#
# usage (from the repository root): bash tests/cli/control.sh build/swarmsim
set -u
sim=${1:-build/swarmsim}
case $sim in /*) ;; *) sim="$PWD/$sim" ;; esac
cd "$(dirname "$0")/../.." || exit 1
tmp=$(mktemp -d "${TMPDIR:-/tmp}/control.XXXXXX") || exit 1
pids=()
trap 'for p in "${pids[@]}"; do kill "$p" 2>/dev/null; done; rm -rf "$tmp"' EXIT
pass=0 fail=0
check() { if eval "$2"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL: $1"; fi; }
. tests/lib/wait_until.sh
py=.venv/bin/python
if ! "$py" -c 'import swarmlcm.control_t' 2>/dev/null; then
    echo "control.sh: $py cannot import the LCM types (swarmlcm): run make deps lcm-types"; exit 1
fi
field() { sed -n "s/^  \"$2\": \"\{0,1\}\([^\",]*\)\"\{0,1\},\{0,1\}\$/\1/p" "$1"; }
rw=sim_host/scenarios/random_walk.yaml
steps=300
# A bus of its own (a free port), so that no other run on this machine is heard.
port=$("$py" -c 'import socket; s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM); s.bind(("", 0)); print(s.getsockname()[1])')
url="udpm://239.255.76.67:$port?ttl=0"
ctl() { "$py" -m swarmtools.control --lcm "$url" --timeout 120 "$@"; }
# A run under control, paused before its first step, in the background.
start() {
    local out=$1; shift
    "$sim" $rw --steps $steps --seed 7 --realtime 50 --control --paused --control-lcm "$url" --quiet \
        --out "$out" "$@" 2>"$out.err" &
    pid=$!
    pids+=($pid)
}

# ---- the run nobody touched
"$sim" $rw --steps $steps --seed 7 --quiet --out "$tmp/plain"
plain=$(field "$tmp/plain/run_7/summary.json" state_hash)
check "the untouched run has a state hash" "[ -n '$plain' ]"

# ---- paused, stepped, resumed: the same run
start "$tmp/paused"
ctl status >"$tmp/s0"
check "--paused: the run waits at step 0" "grep -q 'step 0, paused' '$tmp/s0'"
ctl step 10 --wait-step 10 >"$tmp/s1"
check "step 10: the run did 10 steps and paused again" "grep -q 'step 10, paused' '$tmp/s1'"
# Two statuses later (each about 0.5 s of wall time apart) it is still at 10.
"$py" - "$url" >"$tmp/s2" <<'EOF'
import sys
from swarmtools.control import Controller
c = Controller(sys.argv[1])
first = c.wait(lambda s: True, 120)
later = c.wait(lambda s: s is not first, 120)
later = c.wait(lambda s: s is not later, 120)
print(first.step, later.step, later.paused)
EOF
check "paused, the step counter stops" "[ \"\$(cat '$tmp/s2')\" = '10 10 True' ]"
ctl realtime 1000 >/dev/null
ctl resume >/dev/null
wait "$pid"
check "the controlled run finishes (exit 0)" "[ $? -eq 0 ]"
s=$tmp/paused/run_7/summary.json
check "paused and resumed: the state hash of the untouched run" "[ \"\$(field '$s' state_hash)\" = '$plain' ]"
check "its summary lists the 3 commands and is not touched" \
    "grep -q '\"control\": {\"touched\": false, \"commands\": 3' '$s' && grep -q '\"step\": 0, \"robot\": -1, \"command\": \"step 10\"' '$s' && grep -q '\"step\": 10, \"robot\": -1, \"command\": \"resume\"' '$s'"
"$py" - "$tmp/paused/run_7/telemetry.lcmlog" >"$tmp/events" <<'EOF'
import sys
from swarmtools.telemetry import common
for ev, msg in common.read_log(sys.argv[1], "control.sh"):
    if ev.channel == "SWARM_EVENT" and msg.kind == "control":
        print(msg.utime // 100000, msg.robot_id, msg.detail)
EOF
check "each command is a control event of the telemetry log, at its step" \
    "[ \"\$(cat '$tmp/events' | tr '\n' ';')\" = '0 -1 step 10;10 -1 realtime 1000;10 -1 resume;' ]"
check "the control bus is not in the telemetry log" \
    "! grep -aq 'SWARM_CONTROL' '$tmp/paused/run_7/telemetry.lcmlog'"

# ---- refusals change nothing; a move touches the run
start "$tmp/moved"
ctl move 99 0 0 2>"$tmp/e1"
check "move: a robot that does not exist is refused (exit 1) with the ids" \
    "[ $? -eq 1 ] && grep -q 'no robot 99 in this run (ids 0 to 19)' '$tmp/e1'"
ctl move 2 5 0 2>"$tmp/e2"
check "move: a pose outside the arena is refused with the bounds" "[ $? -eq 1 ] && grep -q 'outside the arena' '$tmp/e2'"
ctl step 0 2>"$tmp/e3"
check "step 0 is refused" "[ $? -eq 1 ] && grep -q 'not a number of control steps' '$tmp/e3'"
ctl status >"$tmp/s3"
check "after three refusals nothing is recorded and the run has not moved" "grep -q 'step 0, paused; 0 command' '$tmp/s3'"
# A command with another key: ignored, said once on the run's stderr.
"$py" - "$url" <<'EOF'
import sys
from swarmtools.control import Controller, CHANNEL, message
c = Controller(sys.argv[1])
c.wait(lambda s: True, 120)
c.lcm.publish(CHANNEL, message("0" * 32, 1, "resume"))
EOF
wait_until 120 "grep -q 'without this run.s key was ignored' '$tmp/moved.err'"
check "a command without the run's key is ignored (said on stderr)" "[ $? -eq 0 ]"
ctl status >"$tmp/s4"
check "... and the run stays paused" "grep -q 'step 0, paused; 0 command' '$tmp/s4'"
ctl select 3 >/dev/null
"$py" - "$url" >"$tmp/detail" <<'EOF'
import sys
from swarmtools.control import Controller
c = Controller(sys.argv[1])
c.wait(lambda s: True, 120)
c.send("step", steps=2)
import time
end = time.monotonic() + 120
while (c.detail is None or c.detail.utime < 200000) and time.monotonic() < end:
    time.sleep(0.05)
d = c.detail
print(d.robot_id, d.controller, int(d.prox_known), len(d.prox), d.n_blobs >= 0)
EOF
check "select 3: ROBOT_DETAIL of robot 3 with its IR readings" "[ \"\$(cat '$tmp/detail')\" = '3 random_walk 1 8 True' ]"
ctl move 2 0.5 -0.25 90 >/dev/null
check "move is done" "[ $? -eq 0 ]"
ctl realtime 1000 >/dev/null
ctl resume >/dev/null
wait "$pid"
s=$tmp/moved/run_7/summary.json
check "a moved robot marks the run touched, the move listed" \
    "grep -q '\"control\": {\"touched\": true, \"commands\": 4' '$s' && grep -q '\"robot\": 2, \"command\": \"move 2 0.5000 -0.2500 1.5708\"' '$s'"
check "... and changes its state hash" "[ \"\$(field '$s' state_hash)\" != '$plain' ]"

# ---- what cannot work
"$sim" $rw --steps 10 --control --quiet --out "$tmp/x1" 2>"$tmp/e"
check "--control without --realtime: exit 2, said" "[ $? -eq 2 ] && grep -q 'needs --realtime' '$tmp/e' && [ ! -e '$tmp/x1' ]"
"$sim" $rw --steps 10 --realtime 10 --control --reps 2 --quiet --out "$tmp/x2" 2>"$tmp/e"
check "--control with --reps 2: exit 2" "[ $? -eq 2 ] && grep -q 'one run' '$tmp/e'"
"$sim" $rw --steps 10 --realtime 10 --paused --quiet --out "$tmp/x3" 2>"$tmp/e"
check "--paused without --control: exit 2" "[ $? -eq 2 ] && grep -q 'not given' '$tmp/e'"
"$sim" $rw --steps 10 --realtime 10 --control --control-lcm 'nosuch://x' --quiet --out "$tmp/x4" 2>"$tmp/e"
check "--control-lcm with a URL no provider takes: exit 2" "[ $? -eq 2 ] && grep -q 'no LCM provider' '$tmp/e'"

echo "control.sh: $pass passed, $fail failed"
[ $fail -eq 0 ]
