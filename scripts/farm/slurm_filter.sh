#!/usr/bin/env bash
# Slurm job array: each task filters one chunk of an EXR sequence with AAF.
#
#   sbatch --array=1-240:24 scripts/farm/slurm_filter.sh 'shots/s010/noisy.####.exr' 'shots/s010/aaf.####.exr'
#
# Task N filters frames N .. N+STEP-1 (STEP = the array step, 24 above; the last
# chunk is clipped to LAST_FRAME). Reruns skip finished frames, so a requeued
# or preempted task completes its chunk; any failed frame fails the task.
#SBATCH --job-name=aaf-filter
#SBATCH --cpus-per-task=8
#SBATCH --mem=4G
#SBATCH --output=aaf-filter.%A_%a.log
set -euo pipefail
input=${1:?usage: slurm_filter.sh INPUT_PATTERN OUTPUT_PATTERN}
output=${2:?usage: slurm_filter.sh INPUT_PATTERN OUTPUT_PATTERN}
aaf=${AAF:-aaf}
first=${SLURM_ARRAY_TASK_ID:?run as a Slurm array task}
step=${SLURM_ARRAY_TASK_STEP:-1}
last=$((first + step - 1))
if [ -n "${LAST_FRAME:-}" ] && [ "$last" -gt "$LAST_FRAME" ]; then last=$LAST_FRAME; fi
exec "$aaf" filter aaf "$input" -o "$output" --frames "${first}-${last}" \
  --threads "${SLURM_CPUS_PER_TASK:-0}" --skip-existing --skip-bad-frames --progress lines
