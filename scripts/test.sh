#!/usr/bin/env bash
# Installs dependencies, builds, and runs the whole test suite with ctest.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/build.sh"
# The compositor test needs a real Blender; without it the test would only skip.
"$root/scripts/install_blender.sh" >/dev/null
cd "$root/build"
ctest --output-on-failure --parallel "$(nproc)" --timeout 600
