# wait_until.sh - sourced by the shell tests: wait_until SECONDS CONDITION
# polls CONDITION (a shell expression) until it holds, or fails (status 1)
# after SECONDS: a bound that only a hang reaches, so that a busy machine
# passes.
wait_until() { local end=$((SECONDS + $1)); until eval "$2"; do [ $SECONDS -ge $end ] && return 1; sleep 0.05; done; }
