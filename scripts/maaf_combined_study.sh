#!/usr/bin/env bash
# The MAAF combined-effects study (Wu et al. 2017, Sec. 6.2, Fig. 12/14) on
# `room` at 320x240: a 1024 spp reference (seed 1000), then renders at
# 8-256 spp (seed 1) with `--aovs maaf6`, each filtered by `aaf filter maaf6`
# (N = 3, CLI defaults) and by its axis-aligned baseline `--pairs 1`; RMSE
# against the reference, timings split into sampling, pre-filtering and
# filtering, the focal-plane pixels' RMSE against their neighbours'. Writes
# the CSV, summary, plot and pictures to scripts/study/results_maaf6 (or
# $AAF_STUDY_OUT); the EXRs they come from go to out/maaf6_study.
# Extra arguments go to maaf6_study (e.g. --width 160 --height 120).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/build.sh"
work="$root/out/maaf6_study"
out="${AAF_STUDY_OUT:-$root/scripts/study/results_maaf6}"
mkdir -p "$work" "$out"
"$root/build/scripts/study/maaf6_study" -o "$work" "$@"
cp "$work/maaf6_study.csv" "$out/"
/usr/bin/python3 "$root/scripts/plot_maaf6_study.py" "$work" "$out"
