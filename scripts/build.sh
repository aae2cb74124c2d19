#!/usr/bin/env bash
# Configures and builds the Release tree in build/ with ninja.
#   scripts/build.sh [CMAKE ARGS]         everything: the tool, the tests, the
#                                         benchmarks, the studies, the Python module
#   scripts/build.sh --tool [CMAKE ARGS]  only the `aaf` tool (scripts/demo.sh);
#                                         a tree already configured for more keeps it
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if [ "${1:-}" = "--tool" ]; then
  shift
  "$root/scripts/deps.sh" tool
  options=()
  [ -f "$root/build/CMakeCache.txt" ] || options=(-DAAF_BUILD_TESTS=OFF -DAAF_BUILD_BENCHMARKS=OFF -DAAF_PYTHON=OFF)
  cmake -S "$root" -B "$root/build" -G Ninja -DCMAKE_BUILD_TYPE=Release "${options[@]}" "$@" >/dev/null
  cmake --build "$root/build" --parallel "$(nproc)" --target aaf
  exit 0
fi
"$root/scripts/deps.sh" all
cmake -S "$root" -B "$root/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DAAF_BUILD_TESTS=ON -DAAF_BUILD_BENCHMARKS=ON -DAAF_PYTHON=ON "$@" >/dev/null
cmake --build "$root/build" --parallel "$(nproc)"
