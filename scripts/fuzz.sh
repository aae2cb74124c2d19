#!/usr/bin/env bash
# Builds the libFuzzer harnesses of tests/fuzz with clang 14 (build-fuzz/,
# -fsanitize=fuzzer,address,undefined) and runs each for SECONDS (default
# 60), AAF_FUZZ_JOBS (default 2) at a time, starting from the committed seeds
# (tests/fuzz/corpus/<harness>/). Runs in fork mode, so one finding does not
# end a harness's run. Prints per harness: executions, coverage, corpus size,
# crashes/ooms/timeouts; reproducers go to build-fuzz/artifacts/<harness>/.
# Exits 1 when any harness found something. Usage: scripts/fuzz.sh [SECONDS] [HARNESS...]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seconds="${1:-60}"
shift || true
harnesses=("$@")
[ ${#harnesses[@]} -gt 0 ] || harnesses=(fuzz_read_aovs fuzz_channel_map fuzz_scene_file fuzz_options)
jobs="${AAF_FUZZ_JOBS:-2}"

"$root/scripts/deps.sh"
if ! dpkg -s clang-14 libfuzzer-14-dev >/dev/null 2>&1; then
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -q
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends clang-14 libfuzzer-14-dev
fi

build="$root/build-fuzz"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++-14 \
  -DAAF_FUZZ=ON -DAAF_BUILD_TESTS=OFF -DAAF_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build "$build" --parallel "$(nproc)" --target "${harnesses[@]}"

# One harness: a working corpus seeded from the committed one (which stays
# small), fork mode with crashes, OOMs and timeouts recorded but not fatal.
# A single allocation over malloc_limit_mb is reported as an OOM: 1 GB, which
# no input of a few KB has a reason to need; 2.1 GB for the EXR reader, since
# OpenEXR itself allocates a header attribute's declared size (up to 2 GB,
# never touched) before finding the file too short for it.
run_one() {
  local name="$1" corpus="$build/corpus/$1" artifacts="$build/artifacts/$1" log="$build/$1.log"
  local malloc_limit=1024
  [ "$name" != fuzz_read_aovs ] || malloc_limit=2100
  rm -rf "$artifacts"  # the counts printed are this run's findings only
  mkdir -p "$corpus" "$artifacts"
  cp -n "$root/tests/fuzz/corpus/$name"/* "$corpus"/ 2>/dev/null || true
  ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    "$build/tests/fuzz/$name" "$corpus" -artifact_prefix="$artifacts/" -max_total_time="$seconds" \
    -fork=1 -ignore_crashes=1 -ignore_ooms=1 -ignore_timeouts=1 -timeout=20 -rss_limit_mb=2048 \
    -malloc_limit_mb=$malloc_limit -max_len=65536 >"$log" 2>&1 || true
}

# A summary line from the last fork-mode status line of the log.
summarise() {
  local name="$1" log="$build/$1.log" artifacts="$build/artifacts/$1"
  local status execs cov corp
  status=$(grep -E '^#[0-9]+: cov:' "$log" | tail -1 || true)
  execs=$(sed -E 's/^#([0-9]+):.*/\1/' <<<"$status")
  cov=$(sed -E 's/.* cov: ([0-9]+).*/\1/' <<<"$status")
  corp=$(ls "$build/corpus/$name" | wc -l)
  local crashes ooms timeouts
  crashes=$(find "$artifacts" -name 'crash-*' | wc -l)
  ooms=$(find "$artifacts" -name 'oom-*' | wc -l)
  timeouts=$(find "$artifacts" -name 'timeout-*' | wc -l)
  printf '%-18s runs %10s  cov %6s  corpus %5s  crashes %s  ooms %s  timeouts %s\n' \
    "$name" "${execs:-0}" "${cov:-0}" "$corp" "$crashes" "$ooms" "$timeouts"
  [ $((crashes + ooms + timeouts)) -eq 0 ]
}

pids=()
for name in "${harnesses[@]}"; do
  run_one "$name" &
  pids+=($!)
  if [ ${#pids[@]} -ge "$jobs" ]; then
    wait "${pids[0]}"
    pids=("${pids[@]:1}")
  fi
done
wait
echo "fuzzing: ${seconds} s per harness, ${jobs} at a time"
failed=0
for name in "${harnesses[@]}"; do summarise "$name" || failed=1; done
exit $failed
