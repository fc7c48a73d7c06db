#!/bin/bash
# A Slurm job array that runs one sweep as N shards, one shard per array task.
#
#   sbatch --array=0-3 docs/slurm-sweep.sh SWEEP OUT [more `eulerdisk sweep` flags]
#
# SWEEP is a sweep file or a built-in name (`eulerdisk sweep list`); OUT is a folder on a
# file system every node sees. Task i writes OUT/shard-i-of-N (N = the array's size, from
# SLURM_ARRAY_TASK_COUNT; an array starting at 1 works too, SLURM_ARRAY_TASK_MIN is
# subtracted). A task that is requeued or rerun resumes: it runs only the points its folder
# has no row for. Afterwards, join the shards (it lists missing and duplicated runs, and
# exits non-zero when runs are missing):
#
#   sbatch --dependency=afterany:<array job id> --wrap "eulerdisk sweep merge OUT --out OUT/merged"
#
# EULERDISK names the binary (default: `eulerdisk` on the PATH). Each task runs as many
# runs at once as it has CPUs (--cpus-per-task).
#SBATCH --job-name=eulerdisk-sweep
#SBATCH --cpus-per-task=1
#SBATCH --output=eulerdisk-sweep-%A_%a.out
set -euo pipefail
sweep=${1:?usage: sbatch --array=0-(N-1) slurm-sweep.sh SWEEP OUT [flags]}
out=${2:?usage: sbatch --array=0-(N-1) slurm-sweep.sh SWEEP OUT [flags]}
shift 2
exec "${EULERDISK:-eulerdisk}" sweep "$sweep" --out "$out" --shard auto \
    --jobs "${SLURM_CPUS_PER_TASK:-1}" --quiet "$@"
