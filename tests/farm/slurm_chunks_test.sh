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
