#!/usr/bin/env bash
# core_is_generic.sh - the simulator outside its tasks (sim_host/core/, the
# models, the public headers, the registry, the command line) names no
# experiment and no controller: none of the three seeds' words (their
# algorithms, baselines and vocabulary), no registered controller's or
# task's name (read from `swarmsim --help`, so a new one is checked without
# editing this file), and it includes nothing of the tasks or of a seed's
# firmware; each seed's code lives in its own folders.
#
# One allowance, narrow and checked: sim_host/core/scenario.c may name
# random_walk, the platform's common controller (firmware/common/), which
# is the default scenario's and its messages' example; nowhere else.
# Citations of the papers ("seed 002's eq 1") are sources, not names, and
# are allowed.  (Under a second.)
set -u
sim=${1:-build/swarmsim}
cd "$(dirname "$0")/../.."
pass=0 fail=0
check() { if [ -z "$2" ]; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL: $1:"; echo "$2" | sed 's/^/    /'; fi; }
generic=(sim_host/core sim_host/models sim_host/include sim_host/*.c sim_host/*.h)

# The three experiments' words: seed 000 (DRTM vs ARTM foraging), seed 002
# (RepAtt vs random walk and ALNS), seed 003 (EAIPP vs PFIAS, TSASR, NNEA).
seed_words='forag|beacon|token|\bdrtm\b|\bartm\b|repatt|chemotaxis|repulsion|attraction|\balns\b|eaipp|pfias|tsasr|\bnnea\b|physarum|phototaxis|\bgather\b'
# Every registered controller and task, from the binary's own lists.
help=$("$sim" --help) || { echo "FAIL: $sim --help"; exit 1; }
names=$(echo "$help" | awk '/^controllers \(/ { on = 1; next } /^tasks \(/ { on = 0 }
    on && /^  [a-z_]+ / && $1 != "idle" { print $1 }')
[ "$(echo "$names" | wc -l)" -ge 10 ] || { echo "FAIL: found only these controllers in --help: $names"; exit 1; }
name_words=$(echo "$names" | grep -v '^random_walk$' | sed 's/.*/\\b&\\b/' | paste -sd'|')
# Task names are also common words (paths, targets): as names they are
# identifiers (paths_task, "paths" in quotes, tasks/paths/).
task_names=$(echo "$help" | awk '/^tasks \(/ { on = 1; next } /^models \(/ { on = 0 } on && /^  [a-z_]+ / { print $1 }')
[ "$(echo "$task_names" | wc -l)" -ge 4 ] || { echo "FAIL: found only these tasks in --help: $task_names"; exit 1; }
task_words=$(echo "$task_names" | sed 's/.*/\\b&_(task|config|t)\\b|"&"|tasks\/&\\b/' | paste -sd'|')

check "seed words in ${generic[*]}" "$(grep -rniE "$seed_words" "${generic[@]}")"
check "controller names in ${generic[*]}" "$(grep -rnE "$name_words" "${generic[@]}")"
check "task names in ${generic[*]}" "$(grep -rnE "$task_words" "${generic[@]}")"
check "random_walk outside its one allowance (sim_host/core/scenario.c)" \
    "$(grep -rn 'random_walk' "${generic[@]}" | grep -v '^sim_host/core/scenario.c:')"
check "${generic[*]} include a task or a seed's firmware" \
    "$(grep -rnE '#include "(tasks|foraging|examples|repatt|eaipp|pfias|tsasr|waypoint)/' "${generic[@]}")"
check "sim_host/core includes the controllers it should look up by name" \
    "$(grep -rnE '#include "(common/random_walk|common/rng)\.h"' sim_host/core sim_host/models)"

# The checks catch what they should (and not a word that merely contains one).
probe=$(mktemp)
for word in 'food tokens' 'Foraging' 'the beacon' 'phototaxis' 'gather robots' 'RepAtt' 'EAIPP chains' \
            'PFIAS' 'tsasr' 'the NNEA baseline' 'Physarum'; do
    echo "/* $word */" > "$probe"
    if grep -qiE "$seed_words" "$probe"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL: the check missed '$word'"; fi
done
for word in 'forager_sense_all' 'nest_beacon' 'waypoint'; do
    echo "/* $word */" > "$probe"
    if grep -qE "$name_words" "$probe"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL: the controller check missed '$word'"; fi
done
for word in 'paths_task' '"targets"' 'tasks/paths'; do
    echo "$word" > "$probe"
    if grep -qE "$task_words" "$probe"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL: the task check missed '$word'"; fi
done
for word in '/* gathered */' '/* key paths */' '/* the targets of a query */'; do
    echo "$word" > "$probe"
    if grep -qiE "$seed_words" "$probe" || grep -qE "$task_words" "$probe"; then
        fail=$((fail + 1)); echo "FAIL: the check matched '$word'"
    else
        pass=$((pass + 1))
    fi
done
rm -f "$probe"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
