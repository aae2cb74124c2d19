#!/usr/bin/env bash
# The Slurm array script filters every chunk of a 5-frame sequence with an
# array step of 2 (tasks 1, 3, 5: the last chunk 5-6 has one frame) without
# LAST_FRAME, as Slurm would run its tasks; a rerun skips the finished frames.
# Usage: slurm_chunks_test.sh AAF_EXECUTABLE WORK_DIR
set -euo pipefail
aaf="$1" work="$2"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
script="$here/../../scripts/farm/slurm_filter.sh"
rm -rf "$work" && mkdir -p "$work"
"$aaf" render grids --frames 1-5 -o "$work/noisy.####.exr" --width 16 --height 12 --spp 2 --progress none
unset LAST_FRAME
for task in 1 3 5 7; do
  AAF="$aaf" SLURM_ARRAY_TASK_ID=$task SLURM_ARRAY_TASK_STEP=2 SLURM_CPUS_PER_TASK=1 \
    bash "$script" "$work/noisy.####.exr" "$work/aaf.####.exr" > "$work/task$task.log" 2>&1 \
    || { echo "FAILED: task $task"; cat "$work/task$task.log"; exit 1; }
done
for frame in 0001 0002 0003 0004 0005; do
  [ -f "$work/aaf.$frame.exr" ] || { echo "FAILED: frame $frame was not filtered"; exit 1; }
done
grep -q "nothing to do" "$work/task7.log" || { echo "FAILED: task 7 (past the end) did not say so"; exit 1; }
AAF="$aaf" SLURM_ARRAY_TASK_ID=5 SLURM_ARRAY_TASK_STEP=2 \
  bash "$script" "$work/noisy.####.exr" "$work/aaf.####.exr" > "$work/rerun.log" 2>&1
grep -q "skipped" "$work/rerun.log" || { echo "FAILED: the rerun did not skip frame 5"; cat "$work/rerun.log"; exit 1; }
echo "OK: every chunk filtered without LAST_FRAME, a rerun skips"

# Bad input: the CLI's exit codes and one error line naming the problem.
expect() {  # expect CODE NAMED -- ENV... -- ARGS...: exit code and the one stderr line
  local code=$1 named=$2 got=0; shift 3
  local env=()
  while [ "$1" != "--" ]; do env+=("$1"); shift; done; shift
  env -u LAST_FRAME AAF="$aaf" SLURM_ARRAY_TASK_ID=1 "${env[@]}" bash "$script" "$@" \
    > "$work/expect.out" 2> "$work/expect.err" || got=$?
  [ "$got" -eq "$code" ] || { cat "$work/expect.err"; echo "FAILED: $* exited $got, expected $code"; exit 1; }
  [ "$(grep -c . "$work/expect.err")" -eq 1 ] && grep -q "^slurm_filter.sh: error: .*$named" "$work/expect.err" \
    || { cat "$work/expect.err"; echo "FAILED: $*: stderr is not one error line naming $named"; exit 1; }
}
mkdir -p "$work/empty"
expect 2 "usage" -- --
expect 2 "usage" -- -- "$work/noisy.####.exr"
expect 2 "LAST_FRAME='abc'" -- LAST_FRAME=abc -- "$work/noisy.####.exr" "$work/bad.####.exr"
expect 2 "SLURM_ARRAY_TASK_ID='x'" -- SLURM_ARRAY_TASK_ID=x -- "$work/noisy.####.exr" "$work/bad.####.exr"
expect 2 "SLURM_ARRAY_TASK_STEP='0'" -- SLURM_ARRAY_TASK_STEP=0 -- "$work/noisy.####.exr" "$work/bad.####.exr"
expect 2 "no frame field" -- -- "$work/noisy.0001.exr" "$work/bad.####.exr"
expect 3 "$work/empty/noisy.####.exr" -- -- "$work/empty/noisy.####.exr" "$work/bad.####.exr"
expect 3 "$work/nosuch/noisy.####.exr" -- -- "$work/nosuch/noisy.####.exr" "$work/bad.####.exr"
ls "$work" | grep -q "^bad\." && { echo "FAILED: a refused task wrote output"; exit 1; }

# The last frame on disk is found in a folder whose name has a space, brackets
# and glob characters, beside stray names that are not the pattern's frames
# (another version, another padding, a non-number): only frame 3 is the last.
odd="$work/shot [1] *'s"
mkdir -p "$odd"
for frame in 0001 0002 0003; do cp "$work/noisy.$frame.exr" "$odd/noisy.$frame.exr"; done
cp "$work/noisy.0001.exr" "$odd/noisy.v2.exr"
cp "$work/noisy.0001.exr" "$odd/noisy.00009.exr"
cp "$work/noisy.0001.exr" "$odd/noisy.9.exr"
cp "$work/noisy.0001.exr" "$odd/noisy.0009.exr.bak"
cp "$work/noisy.0001.exr" "$odd/xnoisy.0009.exr"
AAF="$aaf" SLURM_ARRAY_TASK_ID=3 SLURM_ARRAY_TASK_STEP=4 env -u LAST_FRAME \
  bash "$script" "$odd/noisy.####.exr" "$odd/aaf.####.exr" > "$work/odd.log" 2>&1 \
  || { cat "$work/odd.log"; echo "FAILED: the task in '$odd' failed"; exit 1; }
[ -f "$odd/aaf.0003.exr" ] || { cat "$work/odd.log"; echo "FAILED: frame 3 in '$odd' was not filtered"; exit 1; }
[ "$(ls "$odd" | grep '^aaf' | tr '\n' ' ')" = "aaf.0003.exr " ] || { ls "$odd"; echo "FAILED: other outputs in '$odd'"; exit 1; }
# A '?' too (OpenImageIO cannot open such a path, so only the search is run:
# the chunk past frame 3 has nothing to do).
mkdir -p "$work/what?"
cp "$odd"/noisy.* "$work/what?/"
AAF="$aaf" SLURM_ARRAY_TASK_ID=5 SLURM_ARRAY_TASK_STEP=2 env -u LAST_FRAME \
  bash "$script" "$work/what?/noisy.####.exr" "$work/what?/aaf.####.exr" > "$work/what.log" 2>&1 \
  || { cat "$work/what.log"; echo "FAILED: the search in '$work/what?' failed"; exit 1; }
grep -q "past the last frame 3: nothing to do" "$work/what.log" \
  || { cat "$work/what.log"; echo "FAILED: the last frame in '$work/what?' is not 3"; exit 1; }
echo "OK: bad command lines refused with the CLI's codes; odd folder names and stray files handled"
