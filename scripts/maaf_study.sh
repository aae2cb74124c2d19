#!/usr/bin/env bash
# The MAAF study: for grids and tentacles at 320x240, RMSE of the beauty against
# a 4096 spp reference for MAAF (N = 3, 25 filters) at 4, 9, 16, 25 spp and for
# AAF with adaptive sampling (first pass 9 spp, mu 0.5 .. 6) and its filter;
# timings split into sampling, accumulation and filtering. Writes
# out/maaf_study/maaf_study.csv, a plot and a summary (the AAF spp matching
# MAAF's RMSE, by interpolating AAF's measured curve). Extra arguments go to
# maaf_study (e.g. --scenes grids --width 160 --height 120); AAF_STUDY_OUT picks
# another output folder.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/build.sh"
out="${AAF_STUDY_OUT:-$root/out/maaf_study}"
mkdir -p "$out"
"$root/build/scripts/study/maaf_study" -o "$out/maaf_study.csv" "$@"
/usr/bin/python3 "$root/scripts/plot_maaf_study.py" "$out/maaf_study.csv" "$out/maaf_rmse.png" | tee "$out/summary.txt"
