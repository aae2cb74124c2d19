#!/usr/bin/env bash
# The farm scripts without a scheduler: slurm_aaf.sh run as Slurm runs an
# array task (its environment set here), aaf_submit.sh's dry run, and both
# scripts' answers to bad command lines: the CLI's exit codes (2 usage, 3
# input, 1 other) and one error line naming the problem, nothing written.
# Usage: farm_scripts_test.sh AAF_EXECUTABLE WORK_DIR
set -euo pipefail
aaf=$1 work=$2
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
task="$here/../../scripts/farm/slurm_aaf.sh"
submit="$here/../../scripts/farm/aaf_submit.sh"
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAILED: $*" >&2; exit 1; }
shot="$work/shot [1] it's"
mkdir -p "$shot"
"$aaf" render grids --frames 1001-1005 -o "$shot/noisy.####.exr" --width 16 --height 12 --spp 2 --progress none

# Chunk mode: array task I gets FIRST_FRAME + I*CHUNK_SIZE .., so frame
# numbers past Slurm's MaxArraySize need no index of their own; a method's
# options and --map reach aaf after the patterns.
env -u LAST_FRAME AAF="$aaf" SLURM_ARRAY_TASK_ID=0 SLURM_CPUS_PER_TASK=1 FIRST_FRAME=1001 CHUNK_SIZE=2 \
  bash "$task" filter gaussian "$shot/noisy.####.exr" "$shot/g.####.exr" --sigma 1 --map visibility=vis \
  > "$work/map.log" 2>&1 && fail "a --map to a channel that is not there succeeded"
grep -q "vis" "$work/map.log" || { cat "$work/map.log"; fail "aaf did not get --map"; }
for index in 0 1 2 3; do
  env -u LAST_FRAME AAF="$aaf" SLURM_ARRAY_TASK_ID=$index SLURM_CPUS_PER_TASK=1 FIRST_FRAME=1001 CHUNK_SIZE=2 \
    bash "$task" filter gaussian "$shot/noisy.####.exr" "$shot/g.####.exr" --sigma 1 > "$work/task$index.log" 2>&1 \
    || { cat "$work/task$index.log"; fail "task $index failed"; }
done
grep -q "filter frames 1005-1005" "$work/task2.log" || { cat "$work/task2.log"; fail "task 2 is not frame 1005 alone"; }
grep -q "nothing to do" "$work/task3.log" || fail "task 3 (past the last frame) did not say so"
mkdir -p "$work/local"
"$aaf" filter gaussian "$shot/noisy.####.exr" -o "$work/local/g.####.exr" --frames 1001-1005 --progress none --sigma 1
for frame in 1001 1002 1003 1004 1005; do
  cmp -s "$work/local/g.$frame.exr" "$shot/g.$frame.exr" || fail "frame $frame differs from one local aaf filter run"
done
# A render's chunk; its last frame must be given.
AAF="$aaf" SLURM_ARRAY_TASK_ID=1 FIRST_FRAME=1 LAST_FRAME=3 CHUNK_SIZE=2 \
  bash "$task" render grids "$shot/r.####.exr" --width 16 --height 12 --spp 2 > "$work/render.log" 2>&1 \
  || { cat "$work/render.log"; fail "the render task failed"; }
[ -f "$shot/r.0003.exr" ] && [ ! -e "$shot/r.0001.exr" ] || fail "render task 1 of 1-3 by 2 did not render frame 3 alone"
[ "$(bash "$task" frames-on-disk "$shot/noisy.####.exr")" = "1001 1005" ] || fail "frames-on-disk is not 1001 1005"
echo "OK: chunks by index, options passed through, the same bytes as a local run"

# The dry run: the sbatch line, runnable as printed, and each task's frames.
"$submit" --dry-run --aaf "$aaf" --chunk 2 --cpus 2 --mem 1G --logs "$shot" \
  filter aaf "$shot/noisy.####.exr" "$shot/aaf.####.exr" --light "$work/key light.json" > "$work/dry.txt"
line=$(head -n 1 "$work/dry.txt")
eval "words=($line)"
# shellcheck disable=SC2154
listed=$(printf '%s\n' "${words[@]}")
[ "${words[0]}" = FIRST_FRAME=1001 ] && [ "${words[1]}" = LAST_FRAME=1005 ] && [ "${words[2]}" = CHUNK_SIZE=2 ] \
  || fail "the dry run's environment is not FIRST_FRAME=1001 LAST_FRAME=1005 CHUNK_SIZE=2: $line"
grep -qx -- "--array=0-2" <<< "$listed" || fail "no --array=0-2 in: $line"
grep -qx -- "--cpus-per-task=2" <<< "$listed" || fail "no --cpus-per-task=2 in: $line"
grep -qxF -- "--output=$shot/aaf-filter.%A_%a.log" <<< "$listed" || fail "the log path is not kept in: $line"
grep -qxF -- "$work/key light.json" <<< "$listed" || fail "the --light path is not one word in: $line"
grep -qxF -- "$shot/noisy.####.exr" <<< "$listed" || fail "the input pattern is not one word in: $line"
[ "$(tail -n +2 "$work/dry.txt" | tr '\n' '|')" = "task 0: frames 1001-1002|task 1: frames 1003-1004|task 2: frames 1005-1005|" ] \
  || { cat "$work/dry.txt"; fail "the dry run's tasks are not 1001-1002, 1003-1004, 1005"; }
mkdir -p "$work/100%"
dry=$("$submit" --dry-run --aaf "$aaf" --frames 1-3 --logs "$work/100%" render grids "o.####.exr")
grep -qF -- "--output=$work/100%%/aaf-render.%A_%a.log" <<< "$dry" || fail "a % in the log folder is not escaped as %%"
echo "OK: the dry run prints a runnable sbatch line and each task's frames"

expect() {  # expect CODE SCRIPT_NAME NAMED -- ENV... -- ARGS...: exit code and the one stderr line
  local code=$1 name=$2 named=$3 got=0 script
  shift 4
  local env=()
  while [ "$1" != "--" ]; do env+=("$1"); shift; done
  shift
  # "submit:slurm_aaf.sh": aaf_submit.sh passing on the task script's error.
  case $name in slurm_aaf.sh) script=$task ;; submit:*) script=$submit name=${name#submit:} ;; *) script=$submit ;; esac
  env -u LAST_FRAME -u FIRST_FRAME -u CHUNK_SIZE AAF="$aaf" SLURM_ARRAY_TASK_ID=0 PATH="$(dirname "$aaf"):$PATH" \
    "${env[@]}" bash "$script" "$@" > "$work/expect.out" 2> "$work/expect.err" || got=$?
  [ "$got" -eq "$code" ] || { cat "$work/expect.err"; fail "$name $* exited $got, expected $code"; }
  [ "$(grep -c . "$work/expect.err")" -eq 1 ] && grep -qF "$name: error: " "$work/expect.err" \
    && grep -qF -- "$named" "$work/expect.err" \
    || { cat "$work/expect.err"; fail "$name $*: stderr is not one error line naming $named"; }
}
out="$work/bad.####.exr"
expect 2 slurm_aaf.sh "unknown mode 'paint'" -- -- paint x y
expect 2 slurm_aaf.sh "usage" -- --
expect 2 slurm_aaf.sh "filter needs" -- -- filter aaf "$shot/noisy.####.exr"
expect 2 slurm_aaf.sh "option --frames is set by slurm_aaf.sh" -- -- filter aaf "$shot/noisy.####.exr" "$out" --frames 1-2
expect 2 slurm_aaf.sh "option -o is set" -- -- render grids "$out" -o x.exr
expect 2 slurm_aaf.sh "option --threads is set" -- LAST_FRAME=2 -- render grids "$out" --threads=4
expect 2 slurm_aaf.sh "LAST_FRAME is not set" -- -- render grids "$out"
expect 2 slurm_aaf.sh "SLURM_ARRAY_TASK_ID is not set" -- SLURM_ARRAY_TASK_ID= -- filter aaf "$shot/noisy.####.exr" "$out"
expect 2 slurm_aaf.sh "CHUNK_SIZE='0'" -- CHUNK_SIZE=0 FIRST_FRAME=1 -- filter aaf "$shot/noisy.####.exr" "$out"
expect 2 slurm_aaf.sh "FIRST_FRAME is not set" -- CHUNK_SIZE=2 -- filter aaf "$shot/noisy.####.exr" "$out"
expect 2 slurm_aaf.sh "FIRST_FRAME='x'" -- CHUNK_SIZE=2 FIRST_FRAME=x -- filter aaf "$shot/noisy.####.exr" "$out"
expect 2 slurm_aaf.sh "no frame field" -- -- filter aaf "$shot/noisy.1001.exr" "$out"
expect 3 slurm_aaf.sh "$work/none/noisy.####.exr" -- -- filter aaf "$work/none/noisy.####.exr" "$out"
expect 1 slurm_aaf.sh "cannot run aaf" -- AAF=/nonexistent/aaf LAST_FRAME=1 -- render grids "$out"
expect 2 aaf_submit.sh "render needs --frames" -- -- render grids "$out"
expect 2 aaf_submit.sh "--chunk '0'" -- -- --chunk 0 --frames 1-2 render grids "$out"
expect 2 aaf_submit.sh "--frames '1-2x2'" -- -- --frames 1-2x2 render grids "$out"
expect 2 aaf_submit.sh "--frames '5-2'" -- -- --frames 5-2 render grids "$out"
expect 2 aaf_submit.sh "--mem 'lots'" -- -- --mem lots --frames 1-2 render grids "$out"
expect 2 aaf_submit.sh "unknown option '--bogus'" -- -- --bogus render grids "$out"
expect 2 aaf_submit.sh "backslash" -- -- --logs 'a\b' --frames 1-2 render grids "$out"
expect 2 aaf_submit.sh "--aaf '/nonexistent/aaf'" -- -- --aaf /nonexistent/aaf --frames 1-2 render grids "$out"
expect 3 slurm_aaf.sh "no input frames match" -- -- filter aaf "$work/noisy.####.exr" "$out"
expect 3 submit:slurm_aaf.sh "no input frames match" -- -- --dry-run filter aaf "$work/noisy.####.exr" "$out"
[ -z "$(find "$work" -maxdepth 1 -name 'bad.*')" ] || fail "a refused command wrote output"
echo "OK: bad command lines refused with the CLI's codes and one error line"
