#!/usr/bin/env bash
# Slurm job-array task: renders or filters one chunk of a frame sequence with
# aaf. Submit with scripts/farm/aaf_submit.sh, which computes the array and
# prints the sbatch line (--dry-run); see scripts/farm/README.md.
#
#   slurm_aaf.sh render SCENE OUTPUT_PATTERN [aaf render OPTION...]
#   slurm_aaf.sh filter METHOD INPUT_PATTERN OUTPUT_PATTERN [aaf filter METHOD OPTION...]
#   slurm_aaf.sh frames-on-disk INPUT_PATTERN     (prints "FIRST LAST" of the sequence)
#
# The chunk: with CHUNK_SIZE set, array task I gets the frames
# FIRST_FRAME + I*CHUNK_SIZE .. + CHUNK_SIZE-1 (array indices 0..N-1, so
# frame numbers past Slurm's MaxArraySize work); without it, the task ID is
# the chunk's first frame and the array step its size (sbatch --array=1-240:24).
# Either way the chunk is clipped to LAST_FRAME: for a filter, by default the
# highest input frame on disk; a render needs it.
#
# Every run passes --skip-existing: frames whose output is complete and up to
# date (the provenance in its header) are skipped, stale or partial ones are
# redone, so a requeued, preempted or resubmitted task finishes its chunk and
# nothing partial is ever left under a final name (aaf writes a temporary and
# renames it). A filter also passes --skip-bad-frames: a frame that fails is
# reported and the others are still filtered; the task then fails. aaf render
# has no --skip-bad-frames: a render task stops at its first failed frame.
# The options after the patterns go to aaf as given (--map, --light, a
# method's options, render --filter ...); -o, --frames, --threads,
# --progress and the skip flags are this script's.
# Exit codes are the CLI's: 2 for a bad command line or environment, 3 when
# no input frame is on disk, 1 when aaf cannot be run, else aaf's own.
# AAF names the aaf executable (default: aaf on the PATH); the thread count
# is SLURM_CPUS_PER_TASK (all CPUs when it is not set).
#SBATCH --job-name=aaf
#SBATCH --output=aaf.%A_%a.log
set -euo pipefail
usage="usage: slurm_aaf.sh render SCENE OUTPUT_PATTERN [OPTION...] | filter METHOD INPUT_PATTERN OUTPUT_PATTERN [OPTION...]"
fail() {  # fail CODE MESSAGE: one error line, the CLI's exit code
  echo "slurm_aaf.sh: error: $2" >&2
  exit "$1"
}
# A count of at most 9 digits, so that bash arithmetic cannot overflow.
is_count() { [[ $1 =~ ^[0-9]{1,9}$ ]]; }

# frames_on_disk PATTERN: sets disk_first and disk_last to the lowest and
# highest frame of the sequence on disk, by aaf's rule: a name counts only if
# it is the pattern with its frame field (the first run of # or @, or %0Nd,
# in the file name) replaced by the frame number at that padding. The folder
# and the rest of the name are compared literally, so spaces, brackets and
# glob characters in them mean themselves.
frames_on_disk() {
  local input=$1 folder=. name=$1 prefix padding suffix rest file base number
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
  disk_first= disk_last=
  shopt -s nullglob dotglob
  for file in "$folder"/*; do
    base=${file##*/}
    [[ $base == "$prefix"*"$suffix" ]] || continue
    number=${base#"$prefix"}
    number=${number%"$suffix"}
    is_count "$number" || continue
    [ "$(printf '%0*d' "$((10#$padding))" "$((10#$number))")" = "$number" ] || continue
    number=$((10#$number))
    if [ -z "$disk_last" ] || [ "$number" -gt "$disk_last" ]; then disk_last=$number; fi
    if [ -z "$disk_first" ] || [ "$number" -lt "$disk_first" ]; then disk_first=$number; fi
  done
  shopt -u nullglob dotglob
  [ -n "$disk_last" ] || fail 3 "$input: no input frames match the pattern"
}

mode=${1:-}
case $mode in
  render)
    [ $# -ge 3 ] || fail 2 "render needs a scene and an output pattern; $usage"
    scene=$2 output=$3 input=
    shift 3
    [ -n "$scene" ] && [ -n "$output" ] || fail 2 "an empty scene or pattern; $usage"
    ;;
  filter)
    [ $# -ge 4 ] || fail 2 "filter needs a method, an input and an output pattern; $usage"
    method=$2 input=$3 output=$4
    shift 4
    [ -n "$method" ] && [ -n "$input" ] && [ -n "$output" ] || fail 2 "an empty method or pattern; $usage"
    ;;
  frames-on-disk)
    [ $# -eq 2 ] && [ -n "$2" ] || fail 2 "frames-on-disk needs one input pattern; $usage"
    frames_on_disk "$2"
    echo "$disk_first $disk_last"
    exit 0
    ;;
  *) fail 2 "unknown mode '$mode' (render, filter or frames-on-disk); $usage" ;;
esac
for option in "$@"; do
  case $option in
    -o | --output | --output=* | --frames | --frames=* | --frame | --frame=* | --threads | --threads=* | \
      --progress | --progress=* | --resume | --resume=* | --skip-existing | --skip-bad-frames)
      fail 2 "option ${option%%=*} is set by slurm_aaf.sh (the chunk's frames, the task's CPUs, resumable reruns)"
      ;;
  esac
done

aaf=${AAF:-aaf}
index=${SLURM_ARRAY_TASK_ID:-}
threads=${SLURM_CPUS_PER_TASK:-0}
[ -n "$index" ] || fail 2 "SLURM_ARRAY_TASK_ID is not set: run as a Slurm array task (sbatch --array); $usage"
is_count "$index" || fail 2 "SLURM_ARRAY_TASK_ID='$index' is not a number"
is_count "$threads" || fail 2 "SLURM_CPUS_PER_TASK='$threads' is not a number"
index=$((10#$index))
if [ -n "${CHUNK_SIZE:-}" ]; then
  { is_count "$CHUNK_SIZE" && [ "$((10#$CHUNK_SIZE))" -gt 0 ]; } || fail 2 "CHUNK_SIZE='$CHUNK_SIZE' is not a positive number"
  [ -n "${FIRST_FRAME:-}" ] || fail 2 "FIRST_FRAME is not set (CHUNK_SIZE is): the frame of array task 0"
  is_count "$FIRST_FRAME" || fail 2 "FIRST_FRAME='$FIRST_FRAME' is not a frame number"
  step=$((10#$CHUNK_SIZE))
  first=$((10#$FIRST_FRAME + index * step))
else
  step=${SLURM_ARRAY_TASK_STEP:-1}
  { is_count "$step" && [ "$((10#$step))" -gt 0 ]; } || fail 2 "SLURM_ARRAY_TASK_STEP='$step' is not a positive number"
  step=$((10#$step))
  first=$index
fi
if [ -n "${LAST_FRAME:-}" ]; then
  is_count "$LAST_FRAME" || fail 2 "LAST_FRAME='$LAST_FRAME' is not a frame number"
  last_frame=$((10#$LAST_FRAME))
elif [ "$mode" = render ]; then
  fail 2 "LAST_FRAME is not set: a render's last frame cannot be read from disk"
else
  frames_on_disk "$input"
  last_frame=$disk_last
fi
last=$((first + step - 1))
if [ "$last" -gt "$last_frame" ]; then last=$last_frame; fi
if [ "$first" -gt "$last" ]; then
  echo "slurm_aaf.sh: chunk $first-$((first + step - 1)) is past the last frame $last_frame: nothing to do"
  exit 0
fi
command -v "$aaf" > /dev/null || fail 1 "cannot run aaf ('$aaf'): set AAF to the aaf executable"
echo "slurm_aaf.sh: task $index: $mode frames $first-$last on $(hostname) with ${threads} threads"
# The patterns come first and the user's options last, so an option that
# takes several values (--map, --filter-param) cannot swallow them; aaf then
# records the same command as a local `aaf filter METHOD INPUT -o ... OPTION...`.
if [ "$mode" = render ]; then
  exec "$aaf" render "$scene" -o "$output" --frames "${first}-${last}" --threads "$threads" \
    --skip-existing --progress lines "$@"
fi
exec "$aaf" filter "$method" "$input" -o "$output" --frames "${first}-${last}" --threads "$threads" \
  --skip-existing --skip-bad-frames --progress lines "$@"
