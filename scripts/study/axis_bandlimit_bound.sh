#!/usr/bin/env bash
# Bounds what per-axis light band-limits (a beta along each light axis) could
# gain on the study's two non-square lights (contact 1.6 x 0.5 m, tilted
# 1.4 x 0.7 m, sigma = half the shorter side): the default filter is isotropic
# and takes the sharper (short) axis's equivalent-width sigma_b; an
# anisotropic filter would be at most as wide as the long axis's sigma_b
# everywhere. Filtering the same default adaptive render with the header's
# sigma replaced by each axis's sigma_b (--light-bandlimit sigma then uses it
# as is) gives the short-axis value (must equal the defaults) and the
# long-axis upper bound; a fixed-mu sweep beside them. 320x240, references
# 4096 spp seed 1000, renders seed 1 as in the study. Needs oiiotool.
# Usage: scripts/study/axis_bandlimit_bound.sh [OUT_DIR]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
aaf="$root/build/cli/aaf"
out="${1:-$root/out/axis_bound}"
mkdir -p "$out"
cd "$out"
W=320 H=240
for s in contact tilted; do
  # sigma_b = sigma erf(h / (sigma sqrt 2)) per axis of half-extent h (light_bandlimit.h)
  case $s in
    contact) short=0.17067 long=0.24966 ;;  # sigma 0.25: h 0.25 and 0.8
    tilted) short=0.23894 long=0.33408 ;;   # sigma 0.35: h 0.35 and 0.7
  esac
  [ -f ${s}_ref.exr ] || "$aaf" render $s --width $W --height $H --spp 4096 --seed 1000 -o ${s}_ref.exr 2>/dev/null
  [ -f ${s}_as.exr ] || "$aaf" render $s --adaptive --width $W --height $H --spp 9 --seed 1 -o ${s}_as.exr 2>/dev/null
  oiiotool ${s}_as.exr --attrib "aaf:light:sigma_m" $long -o ${s}_as_long.exr
  oiiotool ${s}_as.exr --attrib "aaf:light:sigma_m" $short -o ${s}_as_short.exr
  rmse() { "$aaf" compare "$1" ${s}_ref.exr | awk '{print $2}'; }
  echo "$s unfiltered $(rmse ${s}_as.exr)"
  "$aaf" filter aaf ${s}_as.exr -o f.exr; echo "$s defaults $(rmse f.exr)"
  "$aaf" filter aaf ${s}_as_short.exr --light-bandlimit sigma -o f.exr; echo "$s isotropic short-axis sigma_b $short (= defaults) $(rmse f.exr)"
  "$aaf" filter aaf ${s}_as_long.exr --light-bandlimit sigma -o f.exr; echo "$s isotropic long-axis sigma_b $long (bound for per-axis) $(rmse f.exr)"
  "$aaf" filter aaf ${s}_as.exr --light-bandlimit sigma -o f.exr; echo "$s sigma $(rmse f.exr)"
  for mu in 1 1.25 1.5 2; do
    "$aaf" filter aaf ${s}_as.exr --fixed-mu --mu $mu -o f.exr; echo "$s fixed mu $mu $(rmse f.exr)"
  done
done
