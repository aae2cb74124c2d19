#!/usr/bin/env bash
# MAAF's partition against its own N = 1 control (scripts/maaf_control/RESULTS.md):
# grids, tentacles and room rendered with the maaf6 AOVs (and grids and
# tentacles with the 4D maaf AOVs) at 9, 16 and 32 spp, four seeds each, at
# 160x120 against 1024 spp references; each filtered with N = 3 and N = 1
# over a sweep of --k with the bands fixed at the render's; RMSE split into
# bias and noise, each N at its best k beside the other, and the paper's
# own comparison (both at k = 1); then maaf6 on room against N = 1 at equal
# time (scripts/maaf_control/equal_time.py). Writes scripts/maaf_control/
# (MAAF_CONTROL_OUT picks another folder). Extra arguments go to
# scripts/maaf_control/control.py (--width, --height, --seeds, --spp, --cases ...).
# Needs Debian's python3-numpy and python3-openimageio.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
aaf="${AAF:-$root/build/cli/aaf}"
[ -x "$aaf" ] || "$root/scripts/build.sh" --tool
out="${MAAF_CONTROL_OUT:-$root/scripts/maaf_control}"
work="${MAAF_CONTROL_WORK:-$(mktemp -d)}"
[ -n "${MAAF_CONTROL_WORK:-}" ] || trap 'rm -rf "$work"' EXIT
/usr/bin/python3 "$root/scripts/maaf_control/control.py" --aaf "$aaf" --out "$out" --work "$work" "$@"
/usr/bin/python3 "$root/scripts/maaf_control/equal_time.py" --aaf "$aaf" --out "$out" --work "$work"
