#!/bin/sh
# A one-node Slurm cluster on this machine for as long as a command runs:
#   cluster.sh COMMAND [ARGS...]
# writes its own slurm.conf and munge key into a fresh temporary folder (nothing in /etc), starts
# munged, slurmctld and slurmd there on free ports of 127.0.0.1 with the machine's real CPUs and
# memory (slurmd -C), waits until the node is idle, runs COMMAND with SLURM_CONF and MUNGE_SOCKET
# set (so sbatch, squeue, sacct, scontrol and sinfo reach it), then stops all three whatever
# happened (a trap) and checks that nothing is left: no process, socket or file of the cluster,
# its temporary folder gone, no new file in the system's Slurm and munge folders. The exit status
# is COMMAND's, or 1 when the cluster did not start or left something behind.
# Runs as root (the daemons and the jobs run as root); needs slurm-wlm and munge
# (tools/install-deps.sh). CLUSTER_KEEP=1 keeps the folder (logs) for a look after a failure.
set -eu

fail() {
    echo "cluster: $*" >&2
    exit 1
}
[ $# -ge 1 ] || fail "usage: cluster.sh COMMAND [ARGS...]"
for p in munged slurmctld slurmd sbatch sinfo scontrol; do
    command -v $p >/dev/null 2>&1 || fail "$p is missing: run tools/install-deps.sh (slurm-wlm, munge)"
done
[ "$(id -u)" -eq 0 ] || fail "the daemons run as root: run as root"

# What the system's own folders of Slurm and munge hold before, to check nothing was added.
system_files() {
    find /etc/slurm /etc/munge /var/lib/slurm /var/log/slurm /var/spool/slurmd \
        /var/spool/slurmctld /var/lib/munge /var/log/munge /run/munge /run/slurm \
        /run/slurmctld.pid /run/slurmd.pid 2>/dev/null | sort
    find /tmp /dev/shm -maxdepth 1 \( -name '*slurm*' -o -name '*munge*' \) \
        ! -name 'sgapi-slurm.*' 2>/dev/null | sort
}
before=$(system_files)

T=$(mktemp -d "${TMPDIR:-/tmp}/sgapi-slurm.XXXXXX")
conf=$T/slurm.conf
sock=$T/munge/munge.socket

# Processes of this cluster: the daemons (their command lines name the folder), the job steps and
# the jobs (their files or environment do).
cluster_processes() {
    for d in /proc/[0-9]*; do
        pid=${d#/proc/}
        [ "$pid" = $$ ] && continue
        if { tr '\0' ' ' <"$d/cmdline"; } 2>/dev/null | grep -qF "$T" ||
            ls -l "$d/fd" 2>/dev/null | grep -qF "$T" ||
            { tr '\0' '\n' <"$d/environ"; } 2>/dev/null | grep -qxF "SLURM_CONF=$conf"; then
            echo "$pid"
        fi
    done
}

# Whether a TCP port of this machine is listening (/proc/net/tcp*: state 0A).
listening() {
    hex=$(printf '%04X' "$1")
    cat /proc/net/tcp /proc/net/tcp6 2>/dev/null |
        awk -v p=":$hex" '$4 == "0A" && substr($2, length($2) - 4) == p { found = 1 }
            END { exit !found }'
}

# Waits up to $2 tenths of a second for process $1 to end.
wait_gone() {
    n=0
    while kill -0 "$1" 2>/dev/null && [ $n -lt "$2" ]; do
        sleep 0.1
        n=$((n + 1))
    done
    ! kill -0 "$1" 2>/dev/null
}

stop() {
    status=$?
    trap - EXIT INT TERM HUP
    set +e
    # The jobs still running first (slurmd kills their steps), then the daemons: SIGTERM is
    # their orderly shutdown.
    if [ -f "$T/slurmctld.pid" ]; then
        SLURM_CONF=$conf MUNGE_SOCKET=$sock timeout 10 scancel --full --quiet --user=root >/dev/null 2>&1
    fi
    # The three at once (each takes a second or two to wind up).
    daemons=""
    for f in slurmd.pid slurmctld.pid munge/munged.pid; do
        [ -s "$T/$f" ] || continue
        pid=$(cat "$T/$f")
        kill -TERM "$pid" 2>/dev/null && daemons="$daemons $pid"
    done
    for pid in $daemons; do
        wait_gone "$pid" 100 || { kill -KILL "$pid" 2>/dev/null; wait_gone "$pid" 20; }
    done
    # No socket: the daemons' TCP ports no longer listen (munge's is in the folder, removed).
    for port in ${ctld_port:-} ${slurmd_port:-}; do
        if listening "$port"; then
            echo "cluster: port $port still listens after the stop" >&2
            status=1
        fi
    done
    left=$(cluster_processes)
    if [ -n "$left" ]; then
        echo "cluster: processes left running after the stop (killed now):" >&2
        for pid in $left; do
            echo "  $pid $({ tr '\0' ' ' <"/proc/$pid/cmdline"; } 2>/dev/null)" >&2
            kill -KILL "$pid" 2>/dev/null
        done
        status=1
    fi
    if [ "${CLUSTER_KEEP:-0}" = 1 ]; then
        echo "cluster: kept $T" >&2
    else
        rm -rf "$T"
        [ -e "$T" ] && { echo "cluster: cannot remove $T" >&2; status=1; }
    fi
    after=$(system_files)
    if [ "$before" != "$after" ]; then
        echo "cluster: files appeared or went in the system's folders:" >&2
        printf '%s\n' "$before" >"${TMPDIR:-/tmp}/sgapi-slurm-before.$$"
        printf '%s\n' "$after" | diff "${TMPDIR:-/tmp}/sgapi-slurm-before.$$" - >&2
        rm -f "${TMPDIR:-/tmp}/sgapi-slurm-before.$$"
        status=1
    fi
    [ $status -eq 0 ] && echo "cluster: stopped; no process, socket or file left"
    exit $status
}
trap stop EXIT
trap 'exit 130' INT
trap 'exit 143' TERM
trap 'exit 129' HUP

mkdir -p "$T/munge" "$T/state" "$T/spool" "$T/log"
# munged wants its socket's folders open to all (they hold nothing secret; the key is 0400).
chmod 755 "$T" "$T/munge"

# A free TCP port of 127.0.0.1 (the kernel's pick, released at once).
free_port() {
    python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'
}
ctld_port=$(free_port)
slurmd_port=$(free_port)
while [ "$slurmd_port" = "$ctld_port" ]; do slurmd_port=$(free_port); done

# munge: a key of its own, its socket, pid, seed and log in the folder.
dd if=/dev/urandom of="$T/munge/munge.key" bs=1024 count=1 2>/dev/null
chmod 400 "$T/munge/munge.key"
munged --socket="$sock" --key-file="$T/munge/munge.key" --pid-file="$T/munge/munged.pid" \
    --seed-file="$T/munge/munged.seed" --log-file="$T/log/munged.log" ||
    fail "munged did not start: $(tail -n 5 "$T/log/munged.log" 2>/dev/null)"

# The node as slurmd sees this machine (CPUs, sockets, cores, threads, memory), named "node0".
node=$(slurmd -C | head -n 1 | sed 's/^NodeName=[^ ]*//; s/ *UpTime.*//')
host=$(hostname -s)
cat >"$conf" <<EOF
ClusterName=sgapi
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$sock,cred_expire=5
CredType=cred/munge
StateSaveLocation=$T/state
SlurmdSpoolDir=$T/spool
SlurmctldPidFile=$T/slurmctld.pid
SlurmdPidFile=$T/slurmd.pid
SlurmctldLogFile=$T/log/slurmctld.log
SlurmdLogFile=$T/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SchedulerType=sched/builtin
# Start a job as soon as CPUs are free (a job that ends frees them), and look at the queue every
# second: a requeued job becomes eligible (after cred_expire) without any event.
SchedulerParameters=batch_sched_delay=0,sched_interval=1
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
DependencyParameters=kill_invalid_depend
ReturnToService=2
MpiDefault=none
SwitchType=switch/none
MailProg=/bin/true
MinJobAge=300
NodeName=node0 NodeAddr=127.0.0.1 NodeHostname=$host$node State=UNKNOWN
PartitionName=batch Nodes=node0 Default=YES MaxTime=INFINITE State=UP
EOF

export SLURM_CONF="$conf" MUNGE_SOCKET="$sock"
slurmctld -f "$conf" || fail "slurmctld did not start: $(tail -n 5 "$T/log/slurmctld.log")"
slurmd -f "$conf" -N node0 || fail "slurmd did not start: $(tail -n 5 "$T/log/slurmd.log")"

n=0
until [ "$(sinfo -h -n node0 -o %T 2>/dev/null)" = idle ]; do
    n=$((n + 1))
    [ $n -lt 300 ] || fail "the node is not idle after 30 s: $(sinfo -h -n node0 -o '%T %E' 2>&1)
$(tail -n 5 "$T/log/slurmctld.log") $(tail -n 5 "$T/log/slurmd.log")"
    sleep 0.1
done
echo "cluster: node0 idle ($(sinfo -h -n node0 -o '%c CPUs, %m MB'), slurmctld on port $ctld_port)"

set +e
"$@"
rc=$?
set -e
exit $rc
