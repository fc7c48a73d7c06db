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
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bin=$(realpath "${1:-target/release/eulerdisk}")
sweep=${2:-paper-friction}
shards=${3:-4}
shift $(( $# < 3 ? $# : 3 ))
[[ ${1:-} == -- ]] && shift
flags=("$@")
[[ ${#flags[@]} -eq 0 ]] && flags=(--set run.t_end=3)
[[ -x $bin ]] || { echo "no binary at $bin: cargo build --release" >&2; exit 2; }
[[ $(id -u) -eq 0 ]] || { echo "run as root" >&2; exit 2; }

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
pgrep -x munged >/dev/null || runuser -u munge -- /usr/sbin/munged
munge -n | unmunge >/dev/null

# A one-node cluster: this machine, all its CPUs, no cgroups, no accounting.
host=$(hostname -s)
mkdir -p /etc/slurm /var/spool/slurmctld /var/spool/slurmd /var/log/slurm
cat > /etc/slurm/slurm.conf <<CONF
ClusterName=check
SlurmctldHost=$host
SlurmUser=root
AuthType=auth/munge
StateSaveLocation=/var/spool/slurmctld
SlurmdSpoolDir=/var/spool/slurmd
SlurmctldLogFile=/var/log/slurm/slurmctld.log
SlurmdLogFile=/var/log/slurm/slurmd.log
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
# A cluster left by an earlier check is stopped the way Slurm stops itself.
if scontrol ping 2>/dev/null | grep -q UP; then
    scontrol shutdown && sleep 2
fi
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
