#!/usr/bin/env bash
# outputs.sh - results you can trust: an output folder never mixes two
# invocations, --replace deletes only what swarmsim made, every summary
# carries its provenance and the effective scenario that reproduces it,
# SIGINT/SIGTERM and a failing sibling repetition leave no file under a
# final name that is not complete, --resume finishes the same aggregate,
# and setups that cannot run are exit-2 errors with no folder.  (About 10 s.)
#
# usage (from the repository root): bash tests/cli/outputs.sh build/swarmsim
set -u
sim=${1:-build/swarmsim}
case $sim in /*) ;; *) sim="$PWD/$sim" ;; esac
cd "$(dirname "$0")/../.." || exit 1
tmp=$(mktemp -d "${TMPDIR:-/tmp}/outputs.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0
check() { if eval "$2"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL: $1"; fi; }
. tests/lib/wait_until.sh
# Byte for byte but the "command" line (its provenance differs on purpose).
same() { cmp -s <(grep -v '^  "command": ' "$1") <(grep -v '^  "command": ' "$2"); }
field() { sed -n "s/^  \"$2\": \"\{0,1\}\([^\",]*\)\"\{0,1\},\{0,1\}\$/\1/p" "$1"; }
rw=sim_host/scenarios/random_walk.yaml
fb=sim_host/scenarios/foraging_base.yaml

# ---- one folder, one invocation
out=$tmp/mix
"$sim" $fb --steps 60 --reps 3 --frames 50 --lcm off --quiet --out "$out"
before=$(cd "$out" && find . -type f | sort | xargs md5sum)
"$sim" $rw --steps 40 --lcm off --quiet --out "$out" 2>"$tmp/err"
check "a non-empty --out is refused (exit 2) and left as it was" \
    "[ $? -eq 2 ] && grep -q 'not empty' '$tmp/err' && [ \"\$(cd '$out' && find . -type f | sort | xargs md5sum)\" = \"\$before\" ]"
"$sim" $rw --steps 40 --lcm off --quiet --out "$out" --replace
check "--replace leaves only the new invocation's files" \
    "[ \"\$(cd '$out' && find . | sort | tr '\n' ' ')\" = '. ./.swarmsim-out ./run_1 ./run_1/.metrics.exact ./run_1/scenario.yaml ./run_1/summary.json ./run_1/timeseries.csv ./scenario.yaml ' ]"
check "--replace: the summary names the new scenario" "[ \"\$(field '$out/run_1/summary.json' scenario)\" = random_walk ]"
mkdir -p "$tmp/home" && echo mine >"$tmp/home/notes.txt"
"$sim" $rw --steps 40 --quiet --out "$tmp/home" --replace 2>"$tmp/err"
check "--replace refuses a folder swarmsim did not make (exit 2), deleting nothing" \
    "[ $? -eq 2 ] && grep -q 'not made by swarmsim' '$tmp/err' && [ \"\$(cat '$tmp/home/notes.txt')\" = mine ]"
"$sim" $rw --steps 40 --quiet --out "$tmp/none" --resume 2>"$tmp/err"
check "--resume of nothing is an error (exit 2)" "[ $? -eq 2 ] && grep -q 'nothing of swarmsim' '$tmp/err'"
"$sim" $rw --steps 41 --lcm off --quiet --out "$out" --resume 2>"$tmp/err"
check "--resume with other settings is refused (exit 2)" "[ $? -eq 2 ] && grep -q 'another invocation' '$tmp/err'"

# ---- make run twice with different scenarios: nothing of the first is left
mk=$tmp/mkrun
make -s --no-print-directory run RUN_OUT="$mk" RUN_ARGS="--steps 1000 --lcm off --quiet" >/dev/null
make -s --no-print-directory run RUN_OUT="$mk" RUN_SCENARIO=$rw RUN_ARGS="--steps 200 --lcm off --quiet" >/dev/null
check "make run twice: only the second scenario's frames and summary" \
    "[ \"\$(ls '$mk/run_1/frames' | tr '\n' ' ')\" = 'frame_000000.png frame_000200.png ' ] && [ \"\$(field '$mk/run_1/summary.json' scenario)\" = random_walk ]"

# ---- provenance, and the effective scenario reproduces the run
pv=$tmp/prov
"$sim" $fb --steps 300 --reps 2 --lcm off --quiet --out "$pv" --set robots.0.policy=artm --set foraging.food_count=12
for f in "$pv/summary.json" "$pv/run_1/summary.json"; do
    check "$f: overrides, policy, code version, command, scenario copy" \
        "grep -q '\"overrides\": \[\"robots.0.policy=artm\", \"foraging.food_count=12\"\]' '$f' && grep -q '\"policy\": \"artm\"' '$f' && [ -n \"\$(field '$f' code_version)\" ] && grep -q '\"command\": \".*--set robots.0.policy=artm' '$f' && grep -q '\"scenario_copy\": \"scenario.yaml\"' '$f'"
done
check "scenario.yaml beside each summary" "[ -s '$pv/scenario.yaml' ] && cmp -s '$pv/scenario.yaml' '$pv/run_2/scenario.yaml'"
"$sim" "$pv/scenario.yaml" --steps 300 --seed 2 --lcm off --quiet --out "$tmp/again"
check "the copied scenario, with no override, reproduces run 2's state hash" \
    "[ \"\$(field '$tmp/again/run_2/summary.json' state_hash)\" = \"\$(field '$pv/run_2/summary.json' state_hash)\" ]"

# ---- SIGINT / SIGTERM during --reps, then --resume
for sig in INT TERM; do
    o=$tmp/stop_$sig
    "$sim" $fb --reps 6 --threads 2 --lcm off --out "$o" >"$tmp/stdout" 2>"$tmp/stderr" &
    p=$!
    # The first whole run (its folder is renamed from run_N.partial when
    # complete), however long a loaded machine takes; then the signal.
    wait_until 600 "[ -d '$o/run_1' ] || [ -d '$o/run_2' ]" || echo "FAIL: SIG$sig: no run finished in 600 s"
    kill -"$sig" $p
    wait $p
    rc=$?
    want=$([ $sig = INT ] && echo 130 || echo 143)
    check "SIG$sig: exit $want" "[ $rc -eq $want ]"
    check "SIG$sig: one line says what was kept and how to continue" \
        "tail -n 1 '$tmp/stderr' | grep -q \"interrupted by SIG$sig: stopped: [0-9] of 6 runs finished.*--resume continues\""
    check "SIG$sig: no temporary or partial file left" "[ -z \"\$(find '$o' -name '*.tmp' -o -name '*.partial')\" ]"
    n=$(ls -d "$o"/run_* 2>/dev/null | wc -l)
    check "SIG$sig: stopped early ($n of 6 finished)" "[ $n -ge 1 ] && [ $n -lt 6 ]"
    check "SIG$sig: the aggregate covers the finished runs" \
        "grep -q '\"reps_done\": $n,' '$o/summary.json' && grep -q '\"complete\": false' '$o/summary.json'"
    bad=0
    for d in "$o"/run_*; do
        [ -s "$d/summary.json" ] && [ "$(wc -l <"$d/timeseries.csv")" -eq 1202 ] || bad=1
    done
    check "SIG$sig: every run folder is complete (summary, 1,201 time-series rows)" "[ $bad -eq 0 ]"
    "$sim" $fb --reps 6 --threads 2 --lcm off --quiet --out "$o" --resume
    check "SIG$sig: --resume finishes (exit 0, 6 of 6)" "[ $? -eq 0 ] && grep -q '\"complete\": true' '$o/summary.json'"
done
"$sim" $fb --reps 6 --threads 2 --lcm off --quiet --out "$tmp/whole"
check "the resumed aggregate equals an uninterrupted one" "same '$tmp/stop_INT/summary.json' '$tmp/whole/summary.json'"

# ---- a failing sibling: a full disk (a 200 kB tmpfs in a private mount
# namespace) fails one repetition while another runs
if unshare -m true 2>/dev/null; then
    fs=$tmp/fs
    mkdir -p "$fs"
    unshare -m sh -c "mount -t tmpfs -o size=200k none '$fs' && '$sim' $fb --reps 4 --threads 2 --lcm off --quiet --out '$fs/out' 2>'$tmp/err'; echo \$? >'$tmp/rc'; find '$fs/out' >'$tmp/files'; for d in '$fs/out'/run_*; do wc -l <\"\$d/timeseries.csv\"; done >'$tmp/rows'"
    check "full disk: exit 1" "[ \"\$(cat '$tmp/rc')\" = 1 ]"
    # Which file meets the full disk first depends on how the two workers
    # interleave (usually a time series; under load it can be another).
    check "full disk: the error names the file" "grep -Eq '/out/[^ ]+: cannot [a-z]+: No space left on device' '$tmp/err'"
    check "full disk: no partial run under a final name" "! grep -q 'partial\|\.tmp' '$tmp/files' && [ -z \"\$(grep -v '^1202\$' '$tmp/rows')\" ]"
else
    echo "FAIL: full disk: cannot make a private mount namespace here (unshare -m); the failing-sibling test did not run"
    fail=$((fail + 1))
fi

# ---- setups that cannot run: exit 2, no folder
cat >"$tmp/crowded.yaml" <<'EOF'
duration: 1
arena: {width: 0.3, height: 0.3}
robots: [{count: 30, controller: random_walk}]
EOF
"$sim" "$tmp/crowded.yaml" --out "$tmp/crowded" 2>"$tmp/err"
check "robots that cannot be placed: exit 2, no folder" "[ $? -eq 2 ] && [ ! -e '$tmp/crowded' ] && grep -q 'cannot place' '$tmp/err'"
cat >"$tmp/grid.yaml" <<'EOF'
duration: 1
robots: [{count: 9, controller: random_walk, placement: {shape: grid, width: 1, height: 1}}]
objects: [{shape: cylinder, x: 0, y: 0, radius: 0.1}]
EOF
"$sim" "$tmp/grid.yaml" --out "$tmp/grid" 2>"$tmp/err"
check "a grid spot on an obstacle names the obstacle and what helps" \
    "[ $? -eq 2 ] && grep -q 'grid spot 5 of 9 at (0.000, 0.000) m is on objects\[0\]' '$tmp/err' && grep -q 'shape: rectangle' '$tmp/err'"
sed -i 's/radius: 0.1}]/radius: 0.1}]\n/; s/shape: grid, width: 1, height: 1/shape: rectangle, width: 1, height: 1/' "$tmp/grid.yaml"
check "...and the advice works" "'$sim' '$tmp/grid.yaml' --lcm off --quiet --out '$tmp/grid2'"

# ---- the edit-and-run loop: without --out, out/<scenario> is the
# scenario's own folder, replaced by each invocation when swarmsim made it
# (and only then); a given --out keeps the refusal and says how to replace.
mkdir -p "$tmp/loop" && printf 'duration: 5\nrobots: [{count: 3, controller: random_walk}]\n' >"$tmp/loop/walk.yaml"
(cd "$tmp/loop" && "$sim" walk.yaml --steps 20 --lcm off --quiet && "$sim" walk.yaml --steps 30 --lcm off --quiet)
check "without --out, a second run replaces out/<scenario>" \
    "[ $? -eq 0 ] && grep -q '\"steps\": 30' '$tmp/loop/out/walk/run_1/summary.json'"
mkdir -p "$tmp/loop2/out/walk" && echo mine >"$tmp/loop2/out/walk/notes.txt" && cp "$tmp/loop/walk.yaml" "$tmp/loop2/walk.yaml"
(cd "$tmp/loop2" && "$sim" walk.yaml --steps 20 --lcm off --quiet 2>"$tmp/err")
check "...but not a folder of that name swarmsim did not make (exit 2, nothing deleted)" \
    "[ $? -eq 2 ] && grep -q 'the default --out: out/walk was not made by swarmsim' '$tmp/err' && [ -e '$tmp/loop2/out/walk/notes.txt' ]"
"$sim" "$tmp/loop/walk.yaml" --steps 20 --lcm off --quiet --out "$tmp/loop/out/walk" 2>"$tmp/err"
check "a given --out that is not empty: exit 2, and the message says how to replace it" \
    "[ $? -eq 2 ] && grep -q 'add --replace to replace it' '$tmp/err'"

# ---- the command line's table: --name=value as --name value, whole names only
"$sim" $rw --steps=25 --lcm=off --quiet --out="$tmp/eq"
check "--name=value works as --name value" "grep -q '\"steps\": 25' '$tmp/eq/run_1/summary.json'"
"$sim" $rw --ste 25 --out "$tmp/abbrev" 2>"$tmp/err"
check "an abbreviation is an unknown option (exit 2, nothing written)" \
    "[ $? -eq 2 ] && grep -q \"unknown option '--ste'\" '$tmp/err' && [ ! -e '$tmp/abbrev' ]"
"$sim" $rw --quiet=yes --out "$tmp/flag" 2>"$tmp/err"
check "a flag given a value is an error" "[ $? -eq 2 ] && grep -q -- '--quiet takes no value' '$tmp/err'"
"$sim" --help >"$tmp/help"
check "--help lists every option of the table, and the models with the HAL calls they serve" \
    "grep -q -- '--video-fps F' '$tmp/help' && grep -q -- '--camera-frames ROBOT' '$tmp/help' && grep -q 'serves: hal_ground' '$tmp/help'"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
