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
seed_words='forag|beacon|token|phototaxis|\bgather\b'
check "seed words in ${generic[*]}" "$(grep -rniE "$seed_words" "${generic[@]}")"
check "${generic[*]} include a task or a seed's firmware" \
    "$(grep -rnE '#include "(tasks|foraging|examples)/' "${generic[@]}")"
check "sim_host/core includes the controllers it should look up by name" \
    "$(grep -rnE '#include "(common/random_walk|common/rng)\.h"' sim_host/core)"
# The check itself catches each seed word (and not a word that merely
# contains one).
probe=$(mktemp)
for word in 'food tokens' 'Foraging' 'the beacon' 'phototaxis' 'gather robots'; do
    echo "/* $word */" > "$probe"
    if grep -qiE "$seed_words" "$probe"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL: the check missed '$word'"; fi
done
echo '/* gathered */' > "$probe"
if grep -qiE "$seed_words" "$probe"; then fail=$((fail + 1)); echo "FAIL: the check matched 'gathered'"; else pass=$((pass + 1)); fi
rm -f "$probe"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
