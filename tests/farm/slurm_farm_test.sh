#!/usr/bin/env bash
# The farm scripts (scripts/farm/aaf_submit.sh, slurm_aaf.sh) on a real
# one-node Slurm cluster started by this test (tests/farm/slurm_cluster.sh:
# slurm-wlm, slurmdbd, munge and mariadb-server, installed with apt-get when
# missing).
#
# Usage: slurm_farm_test.sh CASE AAF_EXECUTABLE WORK_DIR, CASE one of
#   sequence  a 24-frame render and two filters after it (one with
#             --temporal-window 2, whose chunks read the frames around
#             them), 4 tasks each: every task COMPLETED (controller,
#             completion log and sacct), the frames byte-identical to local runs
#   requeue   a task cancelled while a frame is written, then requeued:
#             nothing partial under a final name, its frames then finished
#   resubmit  the same filter job submitted again skips the up-to-date
#             frames and redoes the stale and missing ones
#   node      the node's slurmd and its running tasks killed, slurmd
#             restarted: the tasks are requeued, no finished frame is lost
set -euo pipefail
case=$1 aaf=$2 work=$3
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
submit="$here/../../scripts/farm/aaf_submit.sh"
# shellcheck source=tests/farm/slurm_cluster.sh
source "$here/slurm_cluster.sh"

rm -rf "$work"
mkdir -p "$work"
start_cluster "$work/cluster"
# Frames and logs in a folder whose name has a space, brackets and an
# apostrophe: every path reaches aaf as it was given.
shot="$work/shot 010 [v2] it's"
mkdir -p "$shot/logs"
cd "$work"
size=(--width 32 --height 24 --spp 4)

fail() { echo "FAILED: $*" >&2; cluster_logs >&2; exit 1; }
same_frames() {  # same_frames DIR_A DIR_B NAME FIRST LAST: every frame byte-identical
  local frame name
  for frame in $(seq "$4" "$5"); do
    name=$(printf "%s.%04d.exr" "$3" "$frame")
    [ -f "$2/$name" ] || fail "$2/$name is missing"
    cmp -s "$1/$name" "$2/$name" || fail "$2/$name differs from $1/$name"
  done
}
no_temporaries() {  # no hidden temporary or other stray file left in DIR
  local stray
  stray=$(find "$1" -maxdepth 1 -name '.*.tmp-*')
  [ -z "$stray" ] || fail "temporaries left behind: $stray"
}
stamp() { stat -c '%i %Y.%y' "$1"; }  # inode and modification time: untouched or rewritten
wait_for() {  # wait_for SECONDS DESCRIPTION COMMAND...: until COMMAND succeeds
  local limit=$1 what=$2
  shift 2
  for _ in $(seq $((limit * 10))); do "$@" && return 0; sleep 0.1; done
  fail "waited ${limit}s for $what"
}
has_file() { [ -n "$(find "$1" -maxdepth 1 -name "$2")" ]; }  # has_file DIR NAME_GLOB (DIR literal)
task_state() { scontrol show job -o "$1" | sed -n 's/.* JobState=\([A-Z_]*\) .*/\1/p'; }

case $case in
sequence)
  # The dry run prints the sbatch line and the frames of each task.
  "$submit" --dry-run --aaf "$aaf" --frames 1-24 --chunk 6 --logs "$shot/logs" \
    render grids "$shot/noisy.####.exr" "${size[@]}" > dry.txt
  grep -q -- "--array=0-3 " dry.txt || { cat dry.txt; fail "the dry run's sbatch line has no --array=0-3"; }
  [ "$(grep -c '^task' dry.txt)" -eq 4 ] && grep -qx 'task 3: frames 19-24' dry.txt \
    || { cat dry.txt; fail "the dry run does not list 4 tasks of 6 frames"; }
  render=$("$submit" --aaf "$aaf" --frames 1-24 --chunk 6 --logs "$shot/logs" \
    render grids "$shot/noisy.####.exr" "${size[@]}" --aovs aaf,motion)
  filter=$("$submit" --aaf "$aaf" --frames 1-24 --chunk 6 --logs "$shot/logs" \
    --sbatch "--dependency=afterok:$render" \
    filter aaf "$shot/noisy.####.exr" "$shot/aaf.####.exr" --map position=P --mu 2.5)
  # A temporal window: each task reads the frames around its chunk itself.
  window=$("$submit" --aaf "$aaf" --frames 1-24 --chunk 6 --logs "$shot/logs" \
    --sbatch "--dependency=afterok:$render" \
    filter aaf "$shot/noisy.####.exr" "$shot/window.####.exr" --temporal-window 2)
  wait_job "$render" 120
  wait_job "$filter" 120
  wait_job "$window" 120
  expect_completed "$render" 4
  expect_completed "$filter" 4
  expect_completed "$window" 4
  expect_accounted "$render" 4
  expect_accounted "$filter" 4
  expect_accounted "$window" 4
  for task in 0 1 2 3; do
    [ -f "$shot/logs/aaf-filter.${filter}_$task.log" ] || fail "no log of filter task $task"
  done
  # One local run over the same frames gives the same bytes.
  mkdir -p local
  "$aaf" render grids -o "local/noisy.####.exr" --frames 1-24 "${size[@]}" --aovs aaf,motion --progress none
  same_frames local "$shot" noisy 1 24
  "$aaf" filter aaf "$shot/noisy.####.exr" -o "local/aaf.####.exr" --frames 1-24 --progress none \
    --map position=P --mu 2.5
  same_frames local "$shot" aaf 1 24
  "$aaf" filter aaf "$shot/noisy.####.exr" -o "local/window.####.exr" --frames 1-24 --progress none \
    --temporal-window 2
  same_frames local "$shot" window 1 24
  no_temporaries "$shot"
  echo "OK: 4 render, 4 filter and 4 temporal-window filter tasks COMPLETED on the one-node cluster (sacct agrees); 24 frames each, byte-identical to local runs"
  ;;
requeue)
  mkdir -p ref
  "$aaf" render grids -o "ref/noisy.####.exr" --frames 1-6 "${size[@]}" --progress none
  # aaf's test hook holds each finished temporary for 6 s before renaming it,
  # so the kill lands while a frame is written, its bytes not yet in place:
  # the window must outlast the test's own steps between seeing both frames
  # being written and the signals landing, on a loaded 2-core machine too.
  job=$(AAF_TEST_HOLD_BEFORE_RENAME_S=6 "$submit" --aaf "$aaf" --frames 1-6 --chunk 3 \
    --logs "$shot/logs" render grids "$shot/noisy.####.exr" "${size[@]}")
  # Task 0 (frames 1-3) and task 1 (frames 4-6) each writing its second frame.
  writing() { has_file "$shot" ".noisy.0002.exr.tmp-*" && has_file "$shot" ".noisy.0005.exr.tmp-*"; }
  wait_for 60 "tasks 0 and 1 to write frames 2 and 5" writing
  before1=$(stamp "$shot/noisy.0001.exr") before4=$(stamp "$shot/noisy.0004.exr")
  # Task 0's aaf killed outright (SIGKILL, as the out-of-memory killer does:
  # scancel --signal=KILL is a plain cancel to Slurm); task 1 cancelled with
  # scancel (SIGTERM, then SIGKILL after KillWait).
  victims=$(task_processes "$job" 0)
  [ -n "$victims" ] || fail "no process of task 0 found"
  # shellcheck disable=SC2086
  kill -KILL $victims
  scancel "${job}_1"
  ended() { [ -z "$(squeue -h -j "${job}_0,${job}_1" -t all -o '%T' | grep -v -e FAILED -e CANCELLED)" ]; }
  wait_for 30 "tasks 0 and 1 to end" ended
  [ "$(task_state "${job}_0")" != COMPLETED ] && [ "$(task_state "${job}_1")" = CANCELLED ] \
    || fail "the tasks' states are $(task_state "${job}_0") and $(task_state "${job}_1")"
  # Nothing partial under a final name: the killed frame 2 is not there; the
  # cancelled frame 5, whose bytes were all written, may have been put in
  # place by aaf's SIGTERM handling, whole.
  for frame in 0002 0003 0006; do
    [ ! -e "$shot/noisy.$frame.exr" ] || fail "frame $frame, which the killed tasks had not finished, is under its final name"
  done
  [ ! -e "$shot/noisy.0005.exr" ] || cmp -s "ref/noisy.0005.exr" "$shot/noisy.0005.exr" \
    || fail "frame 5, cancelled while written, is under its final name but not whole"
  scontrol requeue "${job}_0,${job}_1"
  # Slurm makes a requeued job eligible 2 minutes later; here in 3 s (a task
  # started within the second its old credential was revoked is refused).
  scontrol update JobId="${job}_0,${job}_1" StartTime=now+3
  wait_job "$job" 120
  expect_completed "$job" 2
  [ "$(stamp "$shot/noisy.0001.exr")" = "$before1" ] && [ "$(stamp "$shot/noisy.0004.exr")" = "$before4" ] \
    || fail "a requeued task rewrote a frame it had finished"
  grep -q "noisy.0001.exr: skipped" "$shot/logs/aaf-render.${job}_0.log" \
    || { cat "$shot/logs/aaf-render.${job}_0.log"; fail "the requeued task 0 did not skip frame 1"; }
  same_frames ref "$shot" noisy 1 6
  no_temporaries "$shot"
  echo "OK: tasks killed and cancelled mid-frame left nothing partial; requeued, they skipped their finished frames and completed"
  ;;
resubmit)
  "$aaf" render grids -o "$shot/noisy.####.exr" --frames 1-12 "${size[@]}" --progress none
  filter_args=(filter aaf "$shot/noisy.####.exr" "$shot/aaf.####.exr" --map position=P)
  first=$("$submit" --aaf "$aaf" --chunk 3 --logs "$shot/logs" "${filter_args[@]}")
  wait_job "$first" 120
  expect_completed "$first" 4
  for frame in $(seq -f %04g 1 12); do stamps[10#$frame]=$(stamp "$shot/aaf.$frame.exr"); done
  # Frames 3 and 7 rendered again (another seed): their outputs are stale.
  # Frame 10's output is gone.
  sleep 1.1  # a new modification time, as a re-render a second later has
  "$aaf" render grids -o "$shot/noisy.####.exr" --frames 3,7 --seed 9 "${size[@]}" --progress none
  rm "$shot/aaf.0010.exr"
  second=$("$submit" --aaf "$aaf" --chunk 3 --logs "$shot/logs" "${filter_args[@]}")
  wait_job "$second" 120
  expect_completed "$second" 4
  for frame in $(seq 1 12); do
    name=$(printf "aaf.%04d.exr" "$frame")
    if [ "$frame" = 3 ] || [ "$frame" = 7 ] || [ "$frame" = 10 ]; then
      [ "$(stamp "$shot/$name")" != "${stamps[$frame]}" ] || fail "stale or missing $name was not redone"
      ! grep -q "$name: skipped" "$shot"/logs/aaf-filter."$second"_*.log || fail "$name was skipped"
    else
      [ "$(stamp "$shot/$name")" = "${stamps[$frame]}" ] || fail "up-to-date $name was rewritten"
      grep -q "$name: skipped" "$shot"/logs/aaf-filter."$second"_*.log || fail "up-to-date $name was not reported skipped"
    fi
  done
  mkdir -p local
  "$aaf" filter aaf "$shot/noisy.####.exr" -o "local/aaf.####.exr" --frames 1-12 --progress none --map position=P
  same_frames local "$shot" aaf 1 12
  no_temporaries "$shot"
  echo "OK: the second submission skipped 9 up-to-date frames and redid stale 3 and 7 and missing 10"
  ;;
node)
  mkdir -p ref
  "$aaf" render grids -o "ref/noisy.####.exr" --frames 1-12 "${size[@]}" --progress none
  job=$(AAF_TEST_HOLD_BEFORE_RENAME_S=2 "$submit" --aaf "$aaf" --frames 1-12 --chunk 6 \
    --logs "$shot/logs" render grids "$shot/noisy.####.exr" "${size[@]}")
  # Both tasks (frames 1-6, 7-12) past their fourth frame, running for longer
  # than the controller's BatchStartTimeout + MessageTimeout (7 s).
  past_fourth() { [ -f "$shot/noisy.0004.exr" ] && [ -f "$shot/noisy.0010.exr" ]; }
  wait_for 60 "frames 4 and 10" past_fourth
  # The node fails: its slurmd and every process of its tasks die at once.
  finished=()
  for frame in $(seq 1 12); do
    name=$(printf "noisy.%04d.exr" "$frame")
    [ -f "$shot/$name" ] && finished+=("$name")
  done
  stop_slurmd
  kill_job_processes
  declare -A kept
  for name in "${finished[@]}"; do kept[$name]=$(stamp "$shot/$name"); done
  [ ${#finished[@]} -lt 12 ] || fail "the tasks ended before the node failed"
  start_slurmd
  # The controller finds the tasks gone from the node when it registers
  # again and requeues them; Slurm makes a requeued job eligible 2 minutes
  # later: here in 3 s (not within the second its credential was revoked).
  requeued() { [ "$(squeue -h -j "$job" -t PENDING -o '%i' | grep -c .)" -eq 2 ]; }
  wait_for 60 "the controller to requeue both tasks" requeued
  scontrol update JobId="${job}_0,${job}_1" StartTime=now+3
  wait_job "$job" 150
  expect_completed "$job" 2
  for name in "${finished[@]}"; do
    [ "$(stamp "$shot/$name")" = "${kept[$name]}" ] || fail "$name, finished before the failure, was lost or rewritten"
  done
  same_frames ref "$shot" noisy 1 12
  no_temporaries "$shot"
  echo "OK: after the node failed with ${#finished[@]} frames finished, the requeued tasks kept them and finished the rest"
  ;;
*) echo "unknown case '$case'" >&2; exit 2 ;;
esac
