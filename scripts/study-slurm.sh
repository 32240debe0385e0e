#!/usr/bin/env bash
#SBATCH --job-name=rope-study
#SBATCH --array=0-7
#SBATCH --cpus-per-task=4
#SBATCH --mem=2G
#SBATCH --time=01:00:00
#SBATCH --output=rope-study-%A_%a.log
#
# `rope study` as a SLURM job array: each array task runs one shard of the grid.
#
#   rope study [FLAGS] --reference-only --out study/shards/reference   # once, first
#   sbatch scripts/study-slurm.sh [FLAGS]                              # 8 tasks, any nodes
#   rope study --merge study/shards/[0-7] --out study                  # when all have ended
#
# FLAGS are the study's own (scene, --duration, --segments, --dts, …), the same in all three
# commands. OUT (default `study`) and ROPE (default `target/release/rope`) may be set in the
# environment. DRY_RUN=1 prints the task's command line instead of running it, to check the
# script off a cluster: DRY_RUN=1 SLURM_ARRAY_TASK_ID=3 bash scripts/study-slurm.sh
set -euo pipefail
task=${SLURM_ARRAY_TASK_ID:?run this as a SLURM array task (sbatch), or set SLURM_ARRAY_TASK_ID}
shards=${SLURM_ARRAY_TASK_COUNT:-8} # the --array above
out=${OUT:-study}
rope=${ROPE:-target/release/rope}
cmd=("$rope" study "$@" --shard "$task/$shards"
    --reference "$out/shards/reference/reference.json" --out "$out/shards/$task")
if [[ -n ${DRY_RUN:-} ]]; then
    printf '%q ' "${cmd[@]}"
    echo
else
    exec "${cmd[@]}"
fi
