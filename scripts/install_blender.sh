#!/usr/bin/env bash
# Installs Debian's Blender 3.4 (about 300 MB with its dependencies), which the
# Blender tests (tests/blender: the compositor, the bridge, the add-on) need; scripts/test.sh
# runs it, so those tests run rather than report themselves skipped.
set -euo pipefail
if command -v blender >/dev/null; then
  blender --version | head -1
  exit 0
fi
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
$sudo apt-get update -q
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends blender
