#!/bin/bash
# Checks the Slurm path for real on this machine: installs Debian's slurm-wlm and munge (if
# missing), starts a one-node cluster (munged, slurmctld, slurmd), submits
# docs/slurm-sweep.sh as a job array, merges the shards and compares the merged table with
# the same sweep run unsharded, row for row (the timing columns wall_s and cpu_s aside).
#
#   sudo docs/check-slurm-sweep.sh [EULERDISK] [SWEEP] [SHARDS] [-- sweep flags]
#
# Defaults: target/release/eulerdisk, the built-in `paper-friction` sweep with
# `--set run.t_end=3` (12 short runs), 4 shards. Needs root (it installs packages and
# starts daemons) and a Debian-like system; it does not run in CI. Exit 0: equal tables.
#
# Safe on a machine that has Slurm: it refuses to run beside a Slurm controller that is up
# (exit 2, touching nothing); an existing /etc/slurm/slurm.conf is backed up and put back on
# exit, and the daemons it started (slurmctld, slurmd, munged) are stopped on exit, whatever
# the outcome.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bin=$(realpath "${1:-target/release/eulerdisk}")
sweep=${2:-paper-friction}
shards=${3:-4}
shift $(( $# < 3 ? $# : 3 ))
[[ ${1:-} == -- ]] && shift
flags=("$@")
[[ ${#flags[@]} -eq 0 ]] && flags=(--set run.t_end=3)
if command -v scontrol >/dev/null && scontrol ping 2>/dev/null | grep -q UP; then
    echo "a Slurm controller is up on this machine: this check starts a one-node cluster of its" >&2
    echo "own and would disturb it; run it where no Slurm is running" >&2
    exit 2
fi
[[ -x $bin ]] || { echo "no binary at $bin: cargo build --release" >&2; exit 2; }
[[ $(id -u) -eq 0 ]] || { echo "run as root" >&2; exit 2; }

# What this script changes, undone on exit whatever the outcome: the daemons it started are
# stopped (by their pid files), and /etc/slurm/slurm.conf is put back as it was.
conf=/etc/slurm/slurm.conf
backup=""
wrote_conf=no
started_munged=no
started_slurm=no
cleanup() {
    if [[ $started_slurm == yes ]]; then
        scontrol shutdown >/dev/null 2>&1 || true   # stops slurmctld and its slurmd
        sleep 2
        for pidfile in /run/slurmctld-check.pid /run/slurmd-check.pid; do
            [[ -s $pidfile ]] && kill "$(cat "$pidfile")" 2>/dev/null || true
        done
    fi
    if [[ $started_munged == yes && -s /run/munge/munged.pid ]]; then
        kill "$(cat /run/munge/munged.pid)" 2>/dev/null || true
    fi
    if [[ $wrote_conf == yes && -n $backup ]]; then
        mv -f "$backup" "$conf"
    elif [[ $wrote_conf == yes ]]; then
        rm -f "$conf"
    fi
}
trap cleanup EXIT

if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq slurm-wlm munge >/dev/null
fi

# munge: a key, then the daemon as its own user.
if [[ ! -s /etc/munge/munge.key ]]; then
    dd if=/dev/urandom of=/etc/munge/munge.key bs=1024 count=1 status=none
fi
chown munge:munge /etc/munge/munge.key && chmod 400 /etc/munge/munge.key
mkdir -p /run/munge /var/log/munge /var/lib/munge && chown munge:munge /run/munge /var/log/munge /var/lib/munge
if ! pgrep -x munged >/dev/null; then
    runuser -u munge -- /usr/sbin/munged
    started_munged=yes
fi
munge -n | unmunge >/dev/null

# A one-node cluster: this machine, all its CPUs, no cgroups, no accounting.
host=$(hostname -s)
mkdir -p /etc/slurm /var/spool/slurmctld /var/spool/slurmd /var/log/slurm
if [[ -e $conf ]]; then
    backup=$conf.before-eulerdisk-check.$$
    cp -p "$conf" "$backup"
    echo "backed up $conf to $backup (put back on exit)"
fi
wrote_conf=yes
cat > "$conf" <<CONF
ClusterName=check
SlurmctldHost=$host
SlurmUser=root
AuthType=auth/munge
StateSaveLocation=/var/spool/slurmctld
SlurmdSpoolDir=/var/spool/slurmd
SlurmctldLogFile=/var/log/slurm/slurmctld.log
SlurmdLogFile=/var/log/slurm/slurmd.log
SlurmctldPidFile=/run/slurmctld-check.pid
SlurmdPidFile=/run/slurmd-check.pid
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MaxArraySize=1001
NodeName=$host CPUs=$(nproc) State=UNKNOWN
PartitionName=check Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
started_slurm=yes
slurmctld -c
slurmd
for _ in $(seq 60); do
    sinfo -h -o %t 2>/dev/null | grep -q idle && break
    sleep 1
done
sinfo

work=$(mktemp -d /tmp/eulerdisk-slurm-check.XXXXXX)
echo "sweep \`$sweep\` ${flags[*]}: $shards shards via Slurm, results in $work"
job=$(EULERDISK=$bin sbatch --parsable --wait --array=0-$((shards - 1)) --chdir="$work" \
    --export=ALL "$here/slurm-sweep.sh" "$sweep" "$work/sharded" "${flags[@]}")
echo "array job $job done:"
ls "$work/sharded"
"$bin" sweep merge "$work/sharded" --out "$work/merged"
"$bin" sweep "$sweep" --out "$work/unsharded" --quiet "${flags[@]}"

# The last two columns are wall_s and cpu_s (they hold no commas): drop them and compare.
untimed() { sed -E 's/,[^,]*,[^,]*$//' "$1/sweep.csv"; }
if diff <(untimed "$work/merged") <(untimed "$work/unsharded") >/dev/null; then
    echo "OK: merged shards equal the unsharded sweep, $(($(wc -l < "$work/merged/sweep.csv") - 1)) rows"
else
    echo "DIFFERENT: merged shards and unsharded sweep disagree:" >&2
    diff <(untimed "$work/merged") <(untimed "$work/unsharded") >&2 || true
    exit 1
fi
