#!/usr/bin/env bash
# selftest.sh - start a throw-away single-node SLURM cluster with
# local_cluster.sh, run a 4-task job array and a job depending on it, check
# their outputs, stop the cluster and check nothing of it is left running.
# Exits non-zero with the reason on any failure; prints the elapsed seconds.
set -euo pipefail

HERE=$(cd "$(dirname "$0")" && pwd)
CLUSTER=$HERE/local_cluster.sh
PATH=$PATH:/usr/sbin:/sbin
say() { echo "selftest: $*" >&2; }
T0=$(date +%s%N)
elapsed() { echo "$(( ($(date +%s%N) - T0) / 1000000 ))" | sed -E 's/([0-9]{3})$/.\1/; s/^\./0./'; }

if ! bash "$CLUSTER" check; then
    say "FAIL: SLURM/munge programs missing (see above)"
    exit 1
fi

DIR=$(mktemp -d "${TMPDIR:-/tmp}/slurm-selftest.XXXXXX")
STOPPED=0
cleanup() {
    local rc=$?
    if ((!STOPPED)); then
        bash "$CLUSTER" stop "$DIR" || true
    fi
    if ((rc == 0)); then
        rm -rf "$DIR"
    else
        say "logs kept in $DIR"
    fi
    exit "$rc"
}
trap cleanup EXIT
trap 'say "interrupted"; exit 130' INT TERM HUP

fail() {
    say "FAIL: $*"
    if [[ -n ${SLURM_CONF-} ]]; then
        squeue -a 2>/dev/null >&2 || true
        scontrol show job 2>/dev/null | grep -E 'JobId=|JobState=|Reason=' >&2 || true
        for log in "$DIR"/slurmctld.log "$DIR"/slurmd.log; do
            [[ -s $log ]] || continue
            say "---- last lines of $log ----"
            tail -n 20 "$log" >&2
        done
    fi
    say "elapsed $(elapsed) s"
    exit 1
}

# ---- start
line=$(bash "$CLUSTER" start "$DIR") || fail "local_cluster.sh start failed"
[[ $line =~ ^export\ SLURM_CONF=([^[:space:]]+)$ ]] || fail "unexpected start output: '$line'"
eval "$line"
[[ $SLURM_CONF -ef "$DIR/slurm.conf" ]] || fail "SLURM_CONF is $SLURM_CONF, expected $DIR/slurm.conf"
say "cluster up after $(elapsed) s"

# ---- submit
WORK=$DIR/work
mkdir -p "$WORK"
# shellcheck disable=SC2016 # expanded by the job, not here
jid=$(sbatch --parsable --chdir="$WORK" --output="$WORK/slurm-%A_%a.out" --array=0-3 \
    --wrap 'echo $SLURM_ARRAY_TASK_ID > out_$SLURM_ARRAY_TASK_ID') || fail "sbatch of the array failed"
jid=${jid%%;*}
[[ $jid =~ ^[0-9]+$ ]] || fail "sbatch --parsable gave '$jid'"
dep=$(sbatch --parsable --chdir="$WORK" --output="$WORK/slurm-%j.out" --dependency="afterany:$jid" \
    --wrap 'cat out_0 out_1 out_2 out_3 > all') || fail "sbatch of the dependent job failed"
dep=${dep%%;*}
[[ $dep =~ ^[0-9]+$ ]] || fail "sbatch --parsable gave '$dep'"
say "submitted array $jid and dependent job $dep"

# ---- wait (300 s at most: only a hang on a loaded machine reaches it)
done_=0
for ((i = 0; i < 3000; i++)); do
    if q=$(squeue -h -j "$jid,$dep" -o '%i %T' 2>/dev/null); then
        if [[ -z $q ]]; then done_=1; break; fi
    else
        # squeue errors out once the ids are unknown, or when slurmctld is gone
        scontrol ping 2>/dev/null | grep -q 'UP' || fail "slurmctld does not answer"
        done_=1
        break
    fi
    sleep 0.1
done
((done_)) || fail "jobs not finished after 300 s"
say "jobs finished after $(elapsed) s"

# ---- check
states=$(scontrol -o show job "$jid" 2>/dev/null | grep -o 'JobState=[A-Z_]*' | sort | uniq -c | tr -s ' ' | tr '\n' ',')
n_ok=$(scontrol -o show job "$jid" 2>/dev/null | grep -c 'JobState=COMPLETED .*ExitCode=0:0') || true
((n_ok == 4)) || fail "array $jid: $n_ok of 4 tasks COMPLETED with exit 0 (states: $states)"
scontrol -o show job "$dep" 2>/dev/null | grep -q 'JobState=COMPLETED .*ExitCode=0:0' ||
    fail "dependent job $dep did not complete: $(scontrol -o show job "$dep" 2>&1 | grep -o 'JobState=[^ ]*\|Reason=[^ ]*\|ExitCode=[^ ]*' | tr '\n' ' ')"
for t in 0 1 2 3; do
    [[ -f $WORK/out_$t ]] || fail "missing $WORK/out_$t"
    [[ $(cat "$WORK/out_$t") == "$t" ]] || fail "$WORK/out_$t holds '$(cat "$WORK/out_$t")', expected '$t'"
done
[[ -f $WORK/all ]] || fail "missing $WORK/all (dependent job output)"
[[ $(cat "$WORK/all") == $'0\n1\n2\n3' ]] || fail "$WORK/all holds '$(tr '\n' ' ' <"$WORK/all")', expected '0 1 2 3'"
# tasks started in the same second ran side by side (1 CPU each, CR_Core)
par=$(scontrol -o show job "$jid" 2>/dev/null | grep -o 'StartTime=[^ ]*' | sort | uniq -c | sort -rn | awk 'NR==1{print $1}')
say "outputs correct; up to ${par:-?} array tasks started together on $(nproc) CPUs"

# ---- stop, and check that nothing of the cluster is left
pids=$(cat "$DIR"/munged.pid "$DIR"/slurmctld.pid "$DIR"/slurmd.pid 2>/dev/null | tr -dc '0-9\n')
bash "$CLUSTER" stop "$DIR" || fail "local_cluster.sh stop failed"
STOPPED=1
for p in $pids; do
    if [[ -e /proc/$p ]] && ! grep -q '^State:[[:space:]]*Z' "/proc/$p/status" 2>/dev/null; then
        fail "pid $p ($(cat /proc/"$p"/comm 2>/dev/null)) still running after stop"
    fi
done

say "PASS in $(elapsed) s"
echo "slurm selftest: 1 passed, 0 failed ($(elapsed) s)"
