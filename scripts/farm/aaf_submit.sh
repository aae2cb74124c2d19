#!/usr/bin/env bash
# Submits a frame sequence to Slurm as a job array of chunks, each task
# running scripts/farm/slurm_aaf.sh on its frames; prints the job ID.
#
#   aaf_submit.sh [SUBMIT OPTION...] render SCENE OUTPUT_PATTERN [aaf render OPTION...]
#   aaf_submit.sh [SUBMIT OPTION...] filter METHOD INPUT_PATTERN OUTPUT_PATTERN [aaf filter METHOD OPTION...]
#
# Submit options:
#   --frames FIRST-LAST  the frames (a render needs them; a filter defaults to
#                        the input sequence's first and last frame on disk)
#   --chunk N            frames per array task (default 10)
#   --cpus N             CPUs per task, aaf's threads (default 1)
#   --mem SIZE           memory per task, as sbatch --mem (default 2G)
#   --max-running N      at most N tasks at once (sbatch --array=...%N)
#   --logs DIR           the tasks' log folder (default .): DIR/aaf-MODE.JOB_TASK.log
#   --aaf PATH           the aaf executable the tasks run (default: aaf on the PATH)
#   --sbatch ARG         one more sbatch argument, e.g. --sbatch --partition=render
#                        or --sbatch --dependency=afterok:123 (repeatable)
#   --dry-run            print the sbatch command line and each task's frames; submit nothing
#
# Tasks are submitted with --requeue: each is safe to run again (it skips the
# frames already finished), so a task killed or lost with its node can be
# requeued, and submitting the same job again redoes only stale or missing
# frames. Exit codes: 2 for a bad command line, 3 when a filter's input has
# no frames on disk, 1 when sbatch fails, else 0.
set -euo pipefail
usage="usage: aaf_submit.sh [--frames A-B] [--chunk N] [--cpus N] [--mem SIZE] [--logs DIR] [--aaf PATH] [--sbatch ARG]... [--dry-run] (render SCENE OUTPUT | filter METHOD INPUT OUTPUT) [OPTION...]"
fail() {
  echo "aaf_submit.sh: error: $2" >&2
  exit "$1"
}
is_count() { [[ $1 =~ ^[0-9]{1,9}$ ]]; }
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
task_script="$here/slurm_aaf.sh"

frames= chunk=10 cpus=1 mem=2G max_running= logs=. aaf= dry_run=0 extra=()
while [ $# -gt 0 ]; do
  case $1 in
    render | filter) break ;;
    --dry-run) dry_run=1; shift; continue ;;
    --frames | --chunk | --cpus | --mem | --max-running | --logs | --aaf | --sbatch)
      [ $# -ge 2 ] || fail 2 "option $1 needs a value; $usage" ;;
    *) fail 2 "unknown option '$1' before the mode (render or filter); $usage" ;;
  esac
  case $1 in
    --frames) frames=$2 ;;
    --chunk) chunk=$2 ;;
    --cpus) cpus=$2 ;;
    --mem) mem=$2 ;;
    --max-running) max_running=$2 ;;
    --logs) logs=$2 ;;
    --aaf) aaf=$2 ;;
    --sbatch) extra+=("$2") ;;
  esac
  shift 2
done
[ $# -gt 0 ] || fail 2 "no mode (render or filter); $usage"
mode=$1
{ is_count "$chunk" && [ "$((10#$chunk))" -gt 0 ]; } || fail 2 "--chunk '$chunk' is not a positive number"
{ is_count "$cpus" && [ "$((10#$cpus))" -gt 0 ]; } || fail 2 "--cpus '$cpus' is not a positive number"
[ -z "$max_running" ] || { is_count "$max_running" && [ "$((10#$max_running))" -gt 0 ]; } \
  || fail 2 "--max-running '$max_running' is not a positive number"
[[ $mem =~ ^[0-9]+[KMGT]?$ ]] || fail 2 "--mem '$mem' is not a size (e.g. 500M, 4G)"
# sbatch reads % in --output as a pattern (%% is a literal %) and, when the
# name has a backslash, no pattern at all: every task would share one log.
[[ $logs != *\\* ]] || fail 2 "--logs '$logs': a backslash in the log folder stops Slurm naming each task's log"
[ -d "$logs" ] || fail 2 "--logs '$logs': no such folder"
if [ -z "$aaf" ]; then aaf=$(command -v aaf) || fail 2 "no aaf on the PATH: give --aaf PATH"; fi
[ -x "$aaf" ] || fail 2 "--aaf '$aaf': not an executable"
case $aaf in /*) ;; *) aaf="$(cd "$(dirname "$aaf")" && pwd)/$(basename "$aaf")" ;; esac

# The mode's arguments are checked by the task script itself, here, now.
case $mode in
  render) [ $# -ge 3 ] || fail 2 "render needs a scene and an output pattern; $usage" ;;
  filter) [ $# -ge 4 ] || fail 2 "filter needs a method, an input and an output pattern; $usage" ;;
esac
if [ -z "$frames" ]; then
  [ "$mode" = filter ] || fail 2 "render needs --frames FIRST-LAST"
  on_disk=$(bash "$task_script" frames-on-disk "$3") || exit $?  # it said why, one line
  read -r first last <<< "$on_disk"
else
  [[ $frames =~ ^([0-9]{1,9})-([0-9]{1,9})$ ]] || [[ $frames =~ ^([0-9]{1,9})()$ ]] \
    || fail 2 "--frames '$frames' is not FIRST-LAST (e.g. 1001-1100)"
  first=$((10#${BASH_REMATCH[1]})) last=$((10#${BASH_REMATCH[2]:-${BASH_REMATCH[1]}}))
  [ "$first" -le "$last" ] || fail 2 "--frames '$frames': the first frame is after the last"
fi
chunk=$((10#$chunk))
tasks=$(((last - first + chunk) / chunk))
array="0-$((tasks - 1))${max_running:+%$max_running}"
command=(env "FIRST_FRAME=$first" "LAST_FRAME=$last" "CHUNK_SIZE=$chunk" "AAF=$aaf"
  sbatch --parsable --export=ALL --requeue "--array=$array" "--job-name=aaf-$mode"
  "--cpus-per-task=$cpus" "--mem=$mem" "--output=${logs//%/%%}/aaf-$mode.%A_%a.log"
  "${extra[@]}" "$task_script" "$@")
if [ "$dry_run" -eq 1 ]; then
  printf '%q ' "${command[@]:1}" | sed 's/ $//'
  echo
  for ((task = 0; task < tasks; task++)); do
    from=$((first + task * chunk)) to=$((first + task * chunk + chunk - 1))
    if [ "$to" -gt "$last" ]; then to=$last; fi
    echo "task $task: frames $from-$to"
  done
  exit 0
fi
"${command[@]}" || fail 1 "sbatch failed (exit $?)"
