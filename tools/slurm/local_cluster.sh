#!/usr/bin/env bash
# local_cluster.sh - a real single-node SLURM cluster (munged + slurmctld +
# slurmd) living entirely inside one folder, for the project's tests.
#
#   local_cluster.sh start DIR   start it; prints `export SLURM_CONF=DIR/slurm.conf`
#   local_cluster.sh stop DIR    stop what `start DIR` started (logs are kept)
#   local_cluster.sh check       are the programs installed? (else: which packages)
#   local_cluster.sh install     install the missing packages with apt-get (as root),
#                                or say which and exit 1
#
# Everything (munge key/socket, conf, state, spool, pid and log files) is in
# DIR; the ports are picked free at start, so several clusters (or a leftover)
# do not collide, and the system's /etc/slurm and /etc/munge are not used.
# The only line `start` prints on stdout is the export line; every message
# goes to stderr.
# See README.md beside this file.
set -euo pipefail

PROG=local_cluster
say() { echo "$PROG: $*" >&2; }

# program : Debian package providing it
PROGRAMS=(
    munged:munge mungekey:munge munge:munge unmunge:munge
    slurmctld:slurmctld slurmd:slurmd
    sbatch:slurm-client squeue:slurm-client sinfo:slurm-client
    scancel:slurm-client scontrol:slurm-client
)
# Debian puts the daemons in /usr/sbin, which a non-login PATH may lack.
PATH=$PATH:/usr/sbin:/sbin

usage() {
    echo "usage: $0 start DIR | stop DIR | check | install" >&2
    exit 2
}

cmd_check() {
    local p prog pkg missing=() progs=()
    for p in "${PROGRAMS[@]}"; do
        prog=${p%%:*} pkg=${p#*:}
        if ! command -v "$prog" >/dev/null 2>&1; then
            progs+=("$prog")
            [[ " ${missing[*]-} " == *" $pkg "* ]] || missing+=("$pkg")
        fi
    done
    if ((${#missing[@]})); then
        say "missing programs: ${progs[*]}"
        say "install them with: apt-get install -y --no-install-recommends ${missing[*]}"
        return 1
    fi
    return 0
}

# shellcheck source=../make/debian_packages.sh
source "$(dirname "$0")/../make/debian_packages.sh"
cmd_install() {
    install_debian_packages "the SLURM tests" cmd_check slurmctld slurmd slurm-client munge
}

# ---------------------------------------------------------------- paths
set_paths() { # set_paths DIR
    DIR=$1
    CONF=$DIR/slurm.conf
    MUNGE_KEY=$DIR/munge.key
    MUNGE_SOCK=$DIR/munge.sock
    MUNGE_PID=$DIR/munged.pid
    MUNGE_LOG=$DIR/munged.log
    MUNGE_SEED=$DIR/munged.seed
    CTLD_PID=$DIR/slurmctld.pid
    CTLD_LOG=$DIR/slurmctld.log
    SLURMD_PID=$DIR/slurmd.pid
    SLURMD_LOG=$DIR/slurmd.log
    STATE_DIR=$DIR/state
    SPOOL_DIR=$DIR/spool
}

# ---------------------------------------------------------------- stop
# proc_exists PID NAME: PID is in the process table (zombie or not) and its
# command name starts with NAME (guards against a recycled pid).
proc_exists() {
    local pid=$1 name=$2 comm
    [[ $pid =~ ^[0-9]+$ ]] || return 1
    comm=$(cat "/proc/$pid/comm" 2>/dev/null) || return 1
    [[ $comm == "$name"* ]]
}
# proc_alive PID NAME: the same, and not a zombie (a zombie is as good as gone)
proc_alive() {
    proc_exists "$1" "$2" || return 1
    ! grep -q '^State:[[:space:]]*Z' "/proc/$1/status" 2>/dev/null
}

# stop_pid PID NAME: TERM, wait up to 10 s, then KILL and wait up to 5 s.
STOPPED=()
stop_pid() {
    local pid=$1 name=$2 i
    proc_alive "$pid" "$name" || return 0
    STOPPED+=("$pid:$name")
    kill -TERM "$pid" 2>/dev/null || true
    for ((i = 0; i < 100; i++)); do
        proc_alive "$pid" "$name" || return 0
        sleep 0.1
    done
    say "$name (pid $pid) did not stop after SIGTERM; sending SIGKILL"
    kill -KILL "$pid" 2>/dev/null || true
    for ((i = 0; i < 50; i++)); do
        proc_alive "$pid" "$name" || return 0
        sleep 0.1
    done
    say "$name (pid $pid) is still there after SIGKILL"
    return 1
}

# The daemons were orphaned (daemonized), so their parent is pid 1; an init
# that reaps lazily leaves them as zombies for a moment: wait (5 s at most)
# until they have left the process table, so `pgrep` shows nothing after stop.
wait_reaped() {
    local i p left
    for ((i = 0; i < 50; i++)); do
        left=0
        for p in "${STOPPED[@]}"; do
            proc_exists "${p%%:*}" "${p#*:}" && left=1
        done
        ((left)) || return 0
        sleep 0.1
    done
}

stop_pidfile() { # stop_pidfile FILE NAME
    local file=$1 name=$2 pid
    [[ -s $file ]] || return 0
    pid=$(tr -dc '0-9' <"$file")
    stop_pid "$pid" "$name"
}

# slurmstepd processes of this cluster: they inherit SLURM_CONF=$CONF from
# the slurmd we started (the caller's shell may have it too, hence the name
# check).
our_stepds() {
    local p pid
    for p in /proc/[0-9]*; do
        pid=${p#/proc/}
        [[ $(cat "$p/comm" 2>/dev/null) == slurmstepd* ]] || continue
        { tr '\0' '\n' <"$p/environ"; } 2>/dev/null | grep -qxF "SLURM_CONF=$CONF" || continue
        echo "$pid"
    done
}

# descendants PID: the pids of all processes below PID
descendants() {
    local -A kids=()
    local f stat rest pid ppid queue=("$1") out=()
    for f in /proc/[0-9]*/stat; do
        { stat=$(<"$f"); } 2>/dev/null || continue
        pid=${stat%% *}
        rest=${stat##*) }    # after "(comm) ": state ppid ...
        ppid=${rest#* }
        ppid=${ppid%% *}
        kids[$ppid]+=" $pid"
    done
    while ((${#queue[@]})); do
        pid=${queue[0]}
        queue=("${queue[@]:1}")
        for f in ${kids[$pid]-}; do
            out+=("$f")
            queue+=("$f")
        done
    done
    echo "${out[@]-}"
}

cmd_stop() {
    local dir=$1 rc=0 pid i
    [[ -d $dir ]] || { say "stop: $dir: no such folder (nothing to stop)"; return 0; }
    set_paths "$(cd "$dir" && pwd)"
    # Cancel the jobs still queued or running so no job outlives the cluster.
    if [[ -s $CONF && -s $CTLD_PID ]] && proc_alive "$(tr -dc '0-9' <"$CTLD_PID")" slurmctld; then
        if [[ -n $(SLURM_CONF=$CONF timeout 5 squeue -h -o %i 2>/dev/null) ]]; then
            SLURM_CONF=$CONF timeout 5 scancel --full --user="$(id -un)" 2>/dev/null || true
            for ((i = 0; i < 30; i++)); do
                [[ -z $(SLURM_CONF=$CONF timeout 5 squeue -h -t running,completing -o %i 2>/dev/null) ]] && break
                sleep 0.1
            done
        fi
    fi
    stop_pidfile "$SLURMD_PID" slurmd || rc=1
    stop_pidfile "$CTLD_PID" slurmctld || rc=1
    # slurmstepds left behind (slurmd gone before their jobs ended, e.g. when
    # slurmctld had died and the jobs could not be cancelled): they ignore
    # SIGTERM, so kill their job processes and them at once
    for pid in $(our_stepds); do
        # shellcheck disable=SC2046 # one pid per word
        kill -KILL $(descendants "$pid") 2>/dev/null || true
        kill -KILL "$pid" 2>/dev/null || true
        STOPPED+=("$pid:slurmstepd")
    done
    stop_pidfile "$MUNGE_PID" munged || rc=1
    rm -f "$MUNGE_SOCK" "$MUNGE_SOCK.lock"
    ((${#STOPPED[@]} == 0)) || wait_reaped
    return $rc
}

# ---------------------------------------------------------------- start
# two distinct free TCP ports on 127.0.0.1
free_ports() {
    if command -v python3 >/dev/null 2>&1 && python3 - <<'EOF' 2>/dev/null; then return 0; fi
import socket
socks = []
for _ in range(2):
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    socks.append(s)
print(" ".join(str(s.getsockname()[1]) for s in socks))
EOF
    # fallback: random ports nobody answers on
    local ports=() p n
    for ((n = 0; n < 200 && ${#ports[@]} < 2; n++)); do
        p=$((20000 + RANDOM % 30000))
        [[ " ${ports[*]-} " == *" $p "* ]] && continue
        if ! (exec 3<>"/dev/tcp/127.0.0.1/$p") 2>/dev/null; then ports+=("$p"); fi
    done
    ((${#ports[@]} == 2)) || return 1
    echo "${ports[*]}"
}

# daemon_died PIDFILE NAME: the daemon wrote its pid file and is gone since
daemon_died() {
    [[ -s $1 ]] || return 1
    ! proc_alive "$(tr -dc '0-9' <"$1")" "$2"
}

STARTED=0
fail() { # fail MESSAGE [LOG...]
    local msg=$1 log
    shift
    say "start failed: $msg"
    for log in "$@"; do
        if [[ -s $log ]]; then
            say "---- last lines of $log ----"
            tail -n 25 "$log" >&2
        fi
    done
    if ((STARTED)); then
        STARTED=0
        say "stopping what was started in $DIR"
        cmd_stop "$DIR" || true
    fi
    exit 1
}
# on any other way out of a failed start (an unexpected error, a signal)
start_exit() {
    local rc=$?
    if ((rc != 0 && STARTED)); then
        STARTED=0
        say "start failed (exit $rc); stopping what was started in $DIR"
        cmd_stop "$DIR" || true
    fi
    exit "$rc"
}

write_conf() { # write_conf HOST CTLD_PORT SLURMD_PORT
    local host=$1 cport=$2 dport=$3 hw cpus mem topo=""
    cpus=$(nproc)
    # The node's real layout, as slurmd itself sees it, so slurmd's
    # registration matches the conf (a node reporting less than configured
    # would be drained).
    hw=$(env -u SLURM_CONF slurmd -C 2>/dev/null | head -n 1) || hw=""
    if [[ $hw =~ CPUs=([0-9]+) ]]; then cpus=${BASH_REMATCH[1]}; fi
    for f in Boards SocketsPerBoard CoresPerSocket ThreadsPerCore; do
        if [[ $hw =~ $f=([0-9]+) ]]; then topo+=" $f=${BASH_REMATCH[1]}"; fi
    done
    # RealMemory a little below what the machine reports, so a slightly
    # different reading at registration never drains the node (memory is not
    # a consumable resource here anyway: CR_Core).
    mem=""
    if [[ $hw =~ RealMemory=([0-9]+) ]]; then mem=" RealMemory=$((BASH_REMATCH[1] * 9 / 10))"; fi

    cat >"$CONF" <<EOF
# Generated by tools/slurm/local_cluster.sh for a single-node test cluster.
ClusterName=localtest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$cport
SlurmdPort=$dport
SlurmUser=root
SlurmdUser=root

AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$MUNGE_SOCK

# No systemd and no cgroup management here: track job processes through
# /proc parent links and do no task binding/containment.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SwitchType=switch/none
MailProg=/bin/true

SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
SchedulerParameters=sched_interval=1,sched_min_interval=100000,batch_sched_delay=0,bf_interval=1
ReturnToService=2

StateSaveLocation=$STATE_DIR
SlurmdSpoolDir=$SPOOL_DIR
SlurmctldPidFile=$CTLD_PID
SlurmdPidFile=$SLURMD_PID
SlurmctldLogFile=$CTLD_LOG
SlurmdLogFile=$SLURMD_LOG
SlurmctldDebug=info
SlurmdDebug=info

SlurmctldTimeout=30
SlurmdTimeout=30
MessageTimeout=5
InactiveLimit=0
MinJobAge=300
KillWait=2
Waittime=0
TCPTimeout=2

NodeName=$host NodeAddr=127.0.0.1 NodeHostname=$host CPUs=$cpus$topo$mem State=UNKNOWN
PartitionName=debug Nodes=$host Default=YES MaxTime=INFINITE State=UP OverSubscribe=NO
EOF
}

cmd_start() {
    local dir=$1 host ports cport dport i state out
    cmd_check >/dev/null || { say "missing programs; run: $0 check"; exit 1; }
    mkdir -p "$dir"
    set_paths "$(cd "$dir" && pwd)"
    # others may pass through (not list) DIR: a non-root client can then
    # reach the munge socket; the key stays root-only (0400)
    chmod 0711 "$DIR"
    if [[ -e $CONF || -e $MUNGE_KEY ]]; then
        say "$DIR already holds a cluster (slurm.conf or munge.key exists); give a fresh folder"
        exit 1
    fi
    if ((${#MUNGE_SOCK} > 100)); then
        say "$DIR is too long a path for a unix socket ($MUNGE_SOCK)"
        exit 1
    fi
    mkdir -p "$STATE_DIR" "$SPOOL_DIR"
    host=$(hostname -s 2>/dev/null || uname -n)
    host=${host%%.*}

    # ---- munge
    trap start_exit EXIT
    trap 'exit 130' INT TERM HUP
    STARTED=1
    if command -v mungekey >/dev/null 2>&1; then
        mungekey --create --keyfile="$MUNGE_KEY" >&2 || fail "mungekey could not create $MUNGE_KEY"
    else
        dd if=/dev/urandom of="$MUNGE_KEY" bs=1024 count=1 status=none
    fi
    chmod 0400 "$MUNGE_KEY"
    munged --socket="$MUNGE_SOCK" --key-file="$MUNGE_KEY" --pid-file="$MUNGE_PID" \
        --log-file="$MUNGE_LOG" --seed-file="$MUNGE_SEED" --force \
        </dev/null >>"$MUNGE_LOG" 2>&1 || fail "munged did not start" "$MUNGE_LOG"
    # (Each wait below is for an event, generous so that only a hang on a
    # loaded machine reaches it.)
    for ((i = 0; i < 600; i++)); do
        out=$(munge -n -S "$MUNGE_SOCK" 2>/dev/null | unmunge -S "$MUNGE_SOCK" 2>/dev/null) && break
        sleep 0.1
    done
    [[ ${out-} == *"STATUS:"*"Success"* ]] || fail "munge/unmunge round trip through $MUNGE_SOCK failed" "$MUNGE_LOG"

    # ---- slurm.conf
    ports=$(free_ports) || fail "could not find free TCP ports"
    read -r cport dport <<<"$ports"
    write_conf "$host" "$cport" "$dport"
    export SLURM_CONF=$CONF

    # ---- daemons (they daemonize, close our stdout and write their pid files)
    slurmctld -f "$CONF" -i </dev/null >>"$CTLD_LOG" 2>&1 ||
        fail "slurmctld exited with an error" "$CTLD_LOG"
    # slurmd registers right away; when slurmctld is not listening yet it
    # retries only a second later, so wait for slurmctld first (120 s at most)
    for ((i = 0; i < 2400; i++)); do
        timeout 5 scontrol ping 2>/dev/null | grep -q 'is UP' && break
        if ((i % 20 == 19)) && daemon_died "$CTLD_PID" slurmctld; then fail "slurmctld died" "$CTLD_LOG"; fi
        sleep 0.05
    done
    ((i < 2400)) || fail "slurmctld does not answer after 120 s (scontrol ping)" "$CTLD_LOG"
    slurmd -f "$CONF" -N "$host" </dev/null >>"$SLURMD_LOG" 2>&1 ||
        fail "slurmd exited with an error" "$SLURMD_LOG" "$CTLD_LOG"

    # ---- wait for the node to be idle (120 s at most)
    state=""
    for ((i = 0; i < 1200; i++)); do
        state=$(timeout 5 sinfo -h -N -n "$host" -o %T 2>/dev/null | head -n 1) || state=""
        [[ $state == idle ]] && break
        if ((i % 10 == 9)); then
            if daemon_died "$CTLD_PID" slurmctld; then fail "slurmctld died" "$CTLD_LOG"; fi
            if daemon_died "$SLURMD_PID" slurmd; then fail "slurmd died" "$SLURMD_LOG" "$CTLD_LOG"; fi
        fi
        sleep 0.1
    done
    [[ $state == idle ]] ||
        fail "node $host not idle after 120 s (state: '${state:-none: no answer, or no node $host in slurm.conf}')" "$CTLD_LOG" "$SLURMD_LOG"

    STARTED=0
    say "cluster up in $DIR: node $host (${state}), slurmctld port $cport, slurmd port $dport"
    echo "export SLURM_CONF=$CONF"
}

case ${1-} in
start) [[ $# == 2 ]] || usage; cmd_start "$2" ;;
stop) [[ $# == 2 ]] || usage; cmd_stop "$2" ;;
check) [[ $# == 1 ]] || usage; cmd_check >/dev/null ;;
install) [[ $# == 1 ]] || usage; cmd_install >/dev/null ;;
*) usage ;;
esac
