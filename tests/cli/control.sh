#!/usr/bin/env bash
# control.sh - a running simulation steered over LCM (swarmsim --control,
# sim_host/core/control.h): a run paused, stepped and resumed ends with the
# state hash of one nobody touched; its step counter stops while paused and
# moves by exactly N for `step N`; every command is an event of the
# telemetry and a line of summary.json; a moved robot marks the run touched
# (and changes it); a live controller key set on one robot or a group
# changes what that robot does, and touches the run; a command for a
# robot or group that does not exist, a pose outside the arena, a step of
# 0, a key unknown, not live or out of range are refused with a reason and change
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
# Waiting for a step a paused run will not reach: heard, so exit 3 (not 2), saying where it is.
ctl status --wait-step 50 --timeout 2 2>"$tmp/e0"
check "--wait-step a paused run does not reach: exit 3, with its step" \
    "[ $? -eq 3 ] && grep -q 'wait-step 50: not there after 2 s: run 7: step 10, paused' '$tmp/e0'"
ctl step abc 2>"$tmp/e0"
check "step abc: a usage error naming the value" "[ $? -eq 2 ] && grep -q \"'abc' is not a whole number of steps\" '$tmp/e0'"
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
d = c.wait_detail(lambda d: d.utime >= 200000, 120)
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

# ---- a robot's time in its state (ROBOT_DETAIL's state_time_s), step by step
start "$tmp/times" --set robots.0.params.turn_chance=8000   # a tumble every ~8 steps
"$py" - "$url" >"$tmp/times.out" <<'EOF'
import sys
from swarmtools.control import Controller
c = Controller(sys.argv[1])
c.wait(lambda s: True, 120)
c.send("select", robot_id=3)
seen, bad = [], []
for k in range(1, 121):
    c.send("step", steps=1)
    d = c.wait_detail(lambda d: d.utime >= k * 100000, 120)
    seen.append((d.utime / 1e6, d.state, d.state_time_s))
for (t0, s0, a0), (t1, s1, a1) in zip(seen, seen[1:]):
    want = a0 + (t1 - t0) if s1 == s0 else 0.0     # one more period in it, or entered at this step
    if abs(a1 - want) > 1e-3 or not 0 <= a1 <= t1 + 1e-3:
        bad.append((t1, s0, s1, a0, a1))
changes = sum(s0 != s1 for (_, s0, _), (_, s1, _) in zip(seen, seen[1:]))
print("ok" if not bad and changes >= 2 else f"bad {bad[:3]}", changes)
c.send("resume")
EOF
check "state_time_s grows by a period while robot 3 stays in a state and is 0 when it enters one" \
    "grep -q '^ok ' '$tmp/times.out' || { cat '$tmp/times.out'; false; }"
wait "$pid"

# ---- set: a live key of one robot, of a group; refusals change nothing
start "$tmp/set"
detail() {   # `step N` with robot R selected: its pose, group and live keys after
    "$py" - "$url" "$@" <<'EOF'
import sys
from swarmtools.control import Controller
c = Controller(sys.argv[1])
robot, steps = int(sys.argv[2]), int(sys.argv[3])
c.wait(lambda s: True, 120)
c.send("select", robot_id=robot)
at = c.send("step", steps=steps).step + steps
d = c.wait_detail(lambda d: d.robot_id == robot and d.utime >= at * 100000, 120)
print(f"{d.x:.4f} {d.y:.4f} {d.group} " + " ".join(f"{n}={v}" for n, v in zip(d.param_names, d.param_values)))
EOF
}
detail 3 1 >"$tmp/da"
detail 3 30 >"$tmp/d0"
check "ROBOT_DETAIL lists the robot's group and live keys with their values" \
    "grep -q ' random_walk speed_steps_s=500 .*turn_chance=1311' '$tmp/d0'"
ctl set 3 speed_steps_s 0 >/dev/null && ctl set 3 turn_chance 0 >/dev/null
check "set 3 speed_steps_s 0 and turn_chance 0 are done" "[ $? -eq 0 ]"
detail 3 30 >"$tmp/d1"
detail 4 1 >"$tmp/d4"
detail 3 30 >"$tmp/d2"
moved() { awk -v a="$(cut -d' ' -f1,2 "$1")" -v b="$(cut -d' ' -f1,2 "$2")" \
    'BEGIN { split(a, p); split(b, q); d = sqrt((p[1]-q[1])^2 + (p[2]-q[2])^2); exit !(d '"$3"') }'; }
check "robot 3, set to speed 0 and no tumbles, stands (under 1 cm in 3 s)" \
    "grep -q 'speed_steps_s=0 .*turn_chance=0' '$tmp/d2' && moved '$tmp/d1' '$tmp/d2' '< 0.01'"
check "... while it drove 10 cm and more in the 3 s before" "moved '$tmp/da' '$tmp/d0' '> 0.1'"
check "... and robot 4 keeps its own values" "grep -q 'speed_steps_s=500 .*turn_chance=1311' '$tmp/d4'"
ctl set random_walk avoid_enter 400 >/dev/null
check "set GROUP KEY VALUE sets every robot of the group" "[ $? -eq 0 ] && detail 4 1 | grep -q 'avoid_enter=400'"
ctl set 3 speed_steps_s 5000 2>"$tmp/e4"
check "set: a value out of the key's range is refused with the range" \
    "[ $? -eq 1 ] && grep -q 'set: speed_steps_s: 5000 is out of range \[0, 1000\]' '$tmp/e4'"
ctl set 3 speed_steps_s fast 2>"$tmp/e5"
check "set: a value of the wrong type is refused" "[ $? -eq 1 ] && grep -q 'expected an integer' '$tmp/e5'"
ctl set 3 nosuch 1 2>"$tmp/e6"
check "set: an unknown key is refused, the live keys listed" \
    "[ $? -eq 1 ] && grep -q \"random_walk has no key 'nosuch' (live keys: speed_steps_s, \" '$tmp/e6'"
ctl set 99 speed_steps_s 1 2>"$tmp/e7"
check "set: a robot that does not exist is refused, with the ids" "[ $? -eq 1 ] && grep -q 'no robot 99 in this run (ids 0 to 19)\$' '$tmp/e7'"
ctl set nosuch speed_steps_s 1 2>"$tmp/e8"
check "set: a group that does not exist is refused, the groups listed" \
    "[ $? -eq 1 ] && grep -q \"no group 'nosuch' in this run (its groups: random_walk)\" '$tmp/e8'"
ctl status >"$tmp/s5"
check "... the refusals record nothing (3 sets and 6 steps, no more)" "grep -q '; 9 command' '$tmp/s5'"
detail 4 1 >"$tmp/d5"
check "... and change no value" "grep -q 'speed_steps_s=500 .*avoid_enter=400' '$tmp/d5'"
ctl realtime 1000 >/dev/null
ctl resume >/dev/null
wait "$pid"
s=$tmp/set/run_7/summary.json
check "a set marks the run touched, each set listed as done" \
    "grep -q '\"control\": {\"touched\": true' '$s' && grep -q '\"robot\": 3, \"command\": \"set 3 speed_steps_s 0\"' '$s' && grep -q '\"robot\": -1, \"command\": \"set group random_walk avoid_enter 400\"' '$s'"
"$py" - "$tmp/set/run_7/telemetry.lcmlog" >"$tmp/sets" <<'EOF'
import sys
from swarmtools.telemetry import common
for ev, msg in common.read_log(sys.argv[1], "control.sh"):
    if ev.channel == "SWARM_EVENT" and msg.kind == "control" and msg.detail.startswith("set"):
        print(msg.robot_id, msg.detail)
EOF
check "each set is a control event of the telemetry log" \
    "[ \"\$(tr '\n' ';' <'$tmp/sets')\" = '3 set 3 speed_steps_s 0;3 set 3 turn_chance 0;-1 set group random_walk avoid_enter 400;' ]"

# A key its controller's init derives from is not settable while the run goes.
fb=sim_host/scenarios/foraging_base.yaml
"$sim" $fb --steps 5 --seed 7 --quiet --out "$tmp/fplain"
"$sim" $fb --steps 5 --seed 7 --realtime 50 --control --paused --control-lcm "$url" --quiet --out "$tmp/fset" \
    2>"$tmp/fset.err" &
pid=$!
pids+=($pid)
ctl set foragers n_min 3 2>"$tmp/e9"
check "set: a key that is not live is refused, the live ones listed" \
    "[ $? -eq 1 ] && grep -q \"forager's key 'n_min' is not settable while the run goes: its init derives from it (live keys: alpha, beta\" '$tmp/e9'"
ctl set foragers alpha 2000 2>"$tmp/e10"
check "set: a live key out of range is refused" "[ $? -eq 1 ] && grep -q 'alpha: 2000 is out of range' '$tmp/e10'"
ctl realtime 1000 >/dev/null
ctl resume >/dev/null
wait "$pid"
check "... nothing changed: the untouched run's state hash" \
    "grep -q '\"touched\": false' '$tmp/fset/run_7/summary.json' && [ \"\$(field '$tmp/fset/run_7/summary.json' state_hash)\" = \"\$(field '$tmp/fplain/run_7/summary.json' state_hash)\" ]"

# ---- what cannot work
"$sim" $rw --steps 10 --control --quiet --out "$tmp/x1" 2>"$tmp/e"
check "--control without --realtime: exit 2, said" "[ $? -eq 2 ] && grep -q 'needs --realtime' '$tmp/e' && [ ! -e '$tmp/x1' ]"
"$sim" $rw --steps 10 --realtime 10 --control --reps 2 --quiet --out "$tmp/x2" 2>"$tmp/e"
check "--control with --reps 2: exit 2" "[ $? -eq 2 ] && grep -q 'one run' '$tmp/e'"
"$sim" $rw --steps 10 --realtime 10 --paused --quiet --out "$tmp/x3" 2>"$tmp/e"
check "--paused without --control: exit 2" "[ $? -eq 2 ] && grep -q 'not given' '$tmp/e'"
"$sim" $rw --steps 10 --realtime 10 --control --control-lcm 'nosuch://x' --quiet --out "$tmp/x4" 2>"$tmp/e"
check "--control-lcm with a URL no provider takes: exit 2, the option named" "[ $? -eq 2 ] && grep -q '^swarmsim: --control-lcm nosuch://x: no LCM provider' '$tmp/e'"

echo "control.sh: $pass passed, $fail failed"
[ $fail -eq 0 ]
