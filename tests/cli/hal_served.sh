#!/usr/bin/env bash
# hal_served.sh - in the simulator every function of hal/hal.h is served
# exactly once: by the core (sim_host/core/sim_hal.c: identity, clock,
# LEDs), by the platform-neutral hal/hal_common.c, or by one model, whose
# descriptor names it among the calls it serves (swarmsim --help's
# "serves:" lines) and whose folder defines it.  A new HAL channel with no
# model, a model that forgets to list a call, or two that define one fail
# here.  (Under a second.)
set -u
sim=${1:-build/swarmsim}
cd "$(dirname "$0")/../.."
pass=0 fail=0
check() { if [ -z "$2" ]; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL: $1:"; echo "$2" | sed 's/^/    /'; fi; }

calls=$(sed -nE 's/^[a-z_0-9]+[ *]+(hal_[a-z_0-9]+)\(hal_t \*hal.*/\1/p' hal/hal.h | sort -u)
[ "$(echo "$calls" | wc -l)" -ge 20 ] || { echo "FAIL: read only these calls from hal/hal.h: $calls"; exit 1; }
definers() {   # FILES... : "call file" for every hal_* function defined in them
    grep -HnE '^[a-z_0-9]+[ *]+hal_[a-z_0-9]+\(hal_t \*hal' "$@" | grep -vE '\);[[:space:]]*$' |
        sed -E 's/^([^:]+):[0-9]+:[^ ]+[ *]+(hal_[a-z_0-9]+)\(.*/\2 \1/'
}
defined=$(definers sim_host/core/sim_hal.c hal/hal_common.c sim_host/models/*/*.c | sort)
served=$("$sim" --help | awk '/^models \(/ { on = 1; next } on && /^$/ { on = 0 }
    on && /^  [a-z_]+ / { model = $1 } on && /serves:/ { for (k = 2; k <= NF; k++) print $k, model }' | sort)

missing="" twice=""
for c in $calls; do
    n=$(echo "$defined" | grep -c "^$c ")
    [ "$n" -eq 0 ] && missing="$missing $c"
    [ "$n" -gt 1 ] && twice="$twice $(echo "$defined" | grep "^$c " | tr '\n' ' ')"
done
check "hal.h calls the simulator does not define" "$missing"
check "hal.h calls defined more than once" "$twice"
# Each model's list is what its folder defines, and nothing else.
bad=""
while read -r c model; do
    [ -n "$c" ] || continue
    echo "$defined" | grep -q "^$c sim_host/models/$model/" || bad="$bad $model lists $c but sim_host/models/$model/ does not define it;"
done <<<"$served"
while read -r c file; do
    case $file in sim_host/models/*)
        model=${file#sim_host/models/}; model=${model%%/*}
        echo "$served" | grep -qx "$c $model" || bad="$bad sim_host/models/$model/ defines $c but the model does not list it;" ;;
    esac
done <<<"$defined"
check "models' hal_calls against their files" "$bad"
# The core serves only what every robot has.
check "sim_host/core/sim_hal.c serves more than identity, clock and LEDs" \
    "$(echo "$defined" | grep ' sim_host/core/sim_hal.c' | grep -vE '^hal_(robot_id|time_ms|control_period_ms|set_led|set_body_led|set_front_led) ')"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
