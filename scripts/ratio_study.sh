#!/usr/bin/env bash
# The ratio estimator study (scripts/ratio_study/RESULTS.md): on the textured
# multi-light scene `livingroom` at 320x240, 1, 2, 4 and 8 shadow rays per
# light, RMSE and FLIP against a 1024-rays-per-light reference of the ratio,
# full-stochastic and control-variate estimators, each with the bilateral,
# Gaussian and AAF denoisers of `aaf filter ratio`; the error where the
# reference is fully unshadowed; a sweep of the bilateral's parameters at 2
# rays per light; flicker with and without --temporal on a static 6-frame
# sequence. Writes scripts/ratio_study/ (RATIO_STUDY_OUT picks another
# folder). Extra arguments go to scripts/ratio_study.py (--width, --height,
# --spp, --ref-spp, --scene ...). Needs Debian's python3-numpy,
# python3-matplotlib and python3-openimageio.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
aaf="${AAF:-$root/build/cli/aaf}"
"$root/scripts/deps.sh"  # the plots need python3-matplotlib
[ -x "$aaf" ] || "$root/scripts/build.sh"
out="${RATIO_STUDY_OUT:-$root/scripts/ratio_study}"
/usr/bin/python3 "$root/scripts/ratio_study.py" --aaf "$aaf" --out "$out" "$@"
rm -rf "$out/work"
