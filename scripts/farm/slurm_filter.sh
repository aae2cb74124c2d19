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
# Exit codes are the CLI's: 2 for a bad command line or environment, 3 when no
# input frame is on disk, else `aaf filter`'s own.
#SBATCH --job-name=aaf-filter
#SBATCH --cpus-per-task=8
#SBATCH --mem=4G
#SBATCH --output=aaf-filter.%A_%a.log
set -euo pipefail
usage="usage: slurm_filter.sh INPUT_PATTERN OUTPUT_PATTERN (as a Slurm array task)"
fail() {  # fail CODE MESSAGE: one error line, the CLI's exit code
  echo "slurm_filter.sh: error: $2" >&2
  exit "$1"
}
# A count of at most 9 digits, so that bash arithmetic cannot overflow.
is_count() { [[ $1 =~ ^[0-9]{1,9}$ ]]; }

[ $# -eq 2 ] || fail 2 "expected 2 arguments, got $#; $usage"
input=$1 output=$2
[ -n "$input" ] && [ -n "$output" ] || fail 2 "an empty pattern; $usage"
aaf=${AAF:-aaf}
first=${SLURM_ARRAY_TASK_ID:-}
step=${SLURM_ARRAY_TASK_STEP:-1}
threads=${SLURM_CPUS_PER_TASK:-0}
[ -n "$first" ] || fail 2 "SLURM_ARRAY_TASK_ID is not set: run as a Slurm array task (sbatch --array); $usage"
is_count "$first" || fail 2 "SLURM_ARRAY_TASK_ID='$first' is not a frame number"
{ is_count "$step" && [ "$((10#$step))" -gt 0 ]; } || fail 2 "SLURM_ARRAY_TASK_STEP='$step' is not a positive number"
is_count "$threads" || fail 2 "SLURM_CPUS_PER_TASK='$threads' is not a number"
first=$((10#$first)) step=$((10#$step))
last=$((first + step - 1))

if [ -z "${LAST_FRAME:-}" ]; then
  # The highest frame of the input sequence on disk, by aaf's rule: a name
  # counts only if it is the pattern with its frame field (the first run of #
  # or @, or %0Nd, in the file name) replaced by the frame number at that
  # padding. The folder and the rest of the name are compared literally, so
  # spaces, brackets and glob characters in them mean themselves.
  folder=. name=$input
  if [[ $input == */* ]]; then folder=${input%/*} name=${input##*/}; [ -n "$folder" ] || folder=/; fi
  if [[ $name =~ ^([^#@]*)(#+|@+)(.*)$ ]]; then
    prefix=${BASH_REMATCH[1]} padding=${#BASH_REMATCH[2]} suffix=${BASH_REMATCH[3]}
  elif [[ $name =~ ^(.*)%0?([0-9]*)d(.*)$ ]]; then
    # The first %d field: bash's regex is greedy, so match again from the left.
    prefix=${name%%%*} rest=${name#"$prefix"}
    [[ $rest =~ ^%0?([0-9]*)d(.*)$ ]] || fail 2 "$input: cannot read the frame field of the pattern"
    padding=${BASH_REMATCH[1]:-0} suffix=${BASH_REMATCH[2]}
    is_count "$padding" || fail 2 "$input: cannot read the frame field of the pattern"
  else
    fail 2 "$input: no frame field (#, @ or %0Nd) in the file name of the pattern"
  fi
  [ -d "$folder" ] || fail 3 "$input: no input frames: no folder $folder"
  LAST_FRAME=
  shopt -s nullglob dotglob
  for file in "$folder"/*; do
    base=${file##*/}
    [[ $base == "$prefix"*"$suffix" ]] || continue
    number=${base#"$prefix"}
    number=${number%"$suffix"}
    is_count "$number" || continue
    [ "$(printf '%0*d' "$((10#$padding))" "$((10#$number))")" = "$number" ] || continue
    if [ -z "$LAST_FRAME" ] || [ "$((10#$number))" -gt "$LAST_FRAME" ]; then LAST_FRAME=$((10#$number)); fi
  done
  [ -n "$LAST_FRAME" ] || fail 3 "$input: no input frames match the pattern"
else
  is_count "$LAST_FRAME" || fail 2 "LAST_FRAME='$LAST_FRAME' is not a frame number"
  LAST_FRAME=$((10#$LAST_FRAME))
fi
if [ "$last" -gt "$LAST_FRAME" ]; then last=$LAST_FRAME; fi
if [ "$first" -gt "$last" ]; then
  echo "slurm_filter.sh: chunk $first-$((first + step - 1)) is past the last frame $LAST_FRAME: nothing to do"
  exit 0
fi
command -v "$aaf" > /dev/null || fail 1 "cannot run aaf ('$aaf'): set AAF to the aaf executable"
exec "$aaf" filter aaf "$input" -o "$output" --frames "${first}-${last}" \
  --threads "$threads" --skip-existing --skip-bad-frames --progress lines
