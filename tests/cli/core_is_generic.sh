#!/usr/bin/env bash
# core_is_generic.sh - the simulator outside its tasks (sim_host/core/, the
# registry, main.c) names no task and no controller: no seed's words in it,
# and it includes nothing of the tasks or of a seed's firmware (the
# registry's lists are generated from the sources, tools/make/registry.sh);
# each seed's code lives in its own folders.  (Under a second.)
set -u
cd "$(dirname "$0")/../.."
pass=0 fail=0
check() { if [ -z "$2" ]; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL: $1:"; echo "$2" | sed 's/^/    /'; fi; }
generic=(sim_host/core sim_host/*.c sim_host/*.h)
check "seed words in ${generic[*]}" "$(grep -rniE 'forag|beacon|token|phototaxis|\bgather\b' "${generic[@]}")"
check "${generic[*]} include a task or a seed's firmware" \
    "$(grep -rnE '#include "(tasks|foraging|examples)/' "${generic[@]}")"
check "sim_host/core includes the controllers it should look up by name" \
    "$(grep -rnE '#include "(common/random_walk|common/rng)\.h"' sim_host/core)"
# The check itself catches a seed word.
probe=$(mktemp)
echo '/* food tokens */' > "$probe"
if grep -qiE 'forag|beacon|token' "$probe"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL: the check missed a probe"; fi
rm -f "$probe"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
