#!/usr/bin/env bash
# Slurm job array: each task filters one chunk of an EXR sequence with AAF.
#
#   sbatch --array=1-240:24 scripts/farm/slurm_filter.sh 'shots/s010/noisy.####.exr' 'shots/s010/aaf.####.exr'
#
# Task N filters frames N .. N+STEP-1 (STEP = the array step, 24 above; the last
# chunk is clipped to LAST_FRAME, by default the highest input frame on disk, so
# any chunk works without it). Reruns skip frames whose output is complete and
# up to date (--skip-existing compares the provenance in its header), so a
# requeued or preempted task completes its chunk; any failed frame fails the task.
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
if [ -z "${LAST_FRAME:-}" ]; then
  # The highest frame of the input sequence on disk: its frame field (####,
  # @@@@ or %04d) as a glob, the number between the prefix and the suffix.
  glob=$(printf '%s' "$input" | sed -E 's/%0?[0-9]*d/*/; s/[#@]+/*/')
  prefix=${glob%%\**} suffix=${glob#*\*}
  LAST_FRAME=$(for file in $glob; do
    number=${file#"$prefix"} number=${number%"$suffix"}
    [[ $number =~ ^[0-9]+$ ]] && echo $((10#$number))
  done | sort -n | tail -1)
  [ -n "$LAST_FRAME" ] || { echo "slurm_filter.sh: no input frames match $input" >&2; exit 3; }
fi
if [ "$last" -gt "$LAST_FRAME" ]; then last=$LAST_FRAME; fi
if [ "$first" -gt "$last" ]; then
  echo "slurm_filter.sh: chunk $first-$((first + step - 1)) is past the last frame $LAST_FRAME: nothing to do"
  exit 0
fi
exec "$aaf" filter aaf "$input" -o "$output" --frames "${first}-${last}" \
  --threads "${SLURM_CPUS_PER_TASK:-0}" --skip-existing --skip-bad-frames --progress lines
