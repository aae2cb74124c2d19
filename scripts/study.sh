#!/usr/bin/env bash
# Reproduces AAF Fig. 6(c) and the sampling figures of Table 1 with the CLI
# defaults: for the study scenes (grids, tentacles, spheres, tilted, grazing,
# contact) at 320x240, RMSE against a 4096 spp reference versus average spp for
# {NAS, AS} x {UF, NAF, AF}, a fixed-mu sweep and one-setting changes on the
# default adaptive render, and the paper's pipeline; writes out/study/study.csv,
# a plot and summary.txt (the tables). Extra arguments go to aaf_study (e.g.
# --scenes grids --width 160 --height 120); AAF_STUDY_OUT picks another folder.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/build.sh"
out="${AAF_STUDY_OUT:-$root/out/study}"
mkdir -p "$out"
"$root/build/scripts/study/aaf_study" -o "$out/study.csv" "$@"
/usr/bin/python3 "$root/scripts/plot_study.py" "$out/study.csv" "$out/rmse_vs_spp.png" | tee "$out/summary.txt"
