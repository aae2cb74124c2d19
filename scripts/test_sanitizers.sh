#!/usr/bin/env bash
# Builds build-asan/ with GCC and AddressSanitizer + UndefinedBehaviorSanitizer
# (-fsanitize=address,undefined -fno-sanitize-recover=all, -O1 -g) and runs the
# tests most exposed to bad input under them; any report fails the run.
#
# The subset (CI is 2 cores and the whole .ci/run must stay well under 15
# minutes; tests/README.md has the timings): every core, io and methods
# test, the CLI tests of errors, refusals and interrupted writes, and the
# bad-input corpus through the sanitized `aaf`. Left out: the tracer's golden
# and convergence renders and the CLI's end-to-end and consistency renders
# (minutes under ASan, and the corpus drives the tracer on every bad scene),
# the Blender compositor test and the consumer (install) test.
# Extra arguments go to cmake's configure step (e.g. -DCMAKE_CXX_COMPILER_LAUNCHER=ccache).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$root/build-asan"
"$root/scripts/deps.sh"
start=$(date +%s)
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
  -DAAF_SANITIZE=ON -DAAF_BUILD_BENCHMARKS=OFF "$@" >/dev/null
cmake --build "$build" --parallel "$(nproc)" --target aaf aaf_with_toy test_core test_io test_methods
built=$(date +%s)

# -fno-sanitize-recover: the first report ends the process with a non-zero
# code, so the test fails. Leaks inside system libraries are suppressed
# (scripts/lsan_suppressions.txt); matching them needs full stacks at malloc
# (fast_unwind_on_malloc=0), and the summary of suppressions stays off stderr,
# which the bad-input corpus checks line by line.
export ASAN_OPTIONS=detect_leaks=1:fast_unwind_on_malloc=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export LSAN_OPTIONS="suppressions=$root/scripts/lsan_suppressions.txt:print_suppressions=0"
cd "$build"
status=0
ctest --output-on-failure --parallel "$(nproc)" --timeout 600 -R '^(core|io|methods):|^bad inputs:' || status=$?
echo "sanitizers: build $((built - start)) s, tests $(($(date +%s) - built)) s"
exit $status
