#!/usr/bin/env bash
# Issue 15's "each effect alone": renders `room` with one effect at a time
# (--maaf6-effects shadows, defocus, indirect, and all three), filters each
# render with `aaf filter maaf6` (MAAF, N = 3) and `--pairs 1` (its
# axis-aligned baseline), both at the CLI defaults, and writes the beauty
# RMSE of the unfiltered and filtered images against a reference of the same
# effects to scripts/study/results_maaf6/per_effect_WIDTHxHEIGHT.csv.
#
#   scripts/maaf6_per_effect.sh [WIDTH HEIGHT [REFERENCE_SPP [SPP...]]]
#
# Defaults: 320x240 (the combined-effects study's size), a 1024 spp
# reference (seed 1000), renders at 16 and 32 spp (seed 1). About 7 minutes
# on 2 cores.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/build.sh" >/dev/null
aaf="$root/build/cli/aaf"
width="${1:-320}" height="${2:-240}" reference_spp="${3:-1024}"
shift $(( $# < 3 ? $# : 3 ))
spps=("$@")
[ ${#spps[@]} -gt 0 ] || spps=(16 32)
out="$root/scripts/study/results_maaf6"
mkdir -p "$out"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

rmse() {  # test reference -> the beauty's RMSE
    "$aaf" compare "$1" "$2" --json | python3 -c 'import json, sys; print("%.6g" % json.load(sys.stdin)["rmse"])'
}

csv="$work/per_effect.csv"
echo "effects,width,height,spp,reference_spp,unfiltered_rmse,aaf_pairs1_rmse,maaf_n3_rmse" >"$csv"
for effects in shadows defocus indirect all; do
    reference="$work/ref_$effects.exr"
    "$aaf" render room --aovs maaf6 --maaf6-effects "$effects" --width "$width" --height "$height" \
        --spp "$reference_spp" --seed 1000 -o "$reference" --progress none
    for spp in "${spps[@]}"; do
        noisy="$work/${effects}_$spp.exr"
        "$aaf" render room --aovs maaf6 --maaf6-effects "$effects" --width "$width" --height "$height" \
            --spp "$spp" --seed 1 -o "$noisy" --progress none
        "$aaf" filter maaf6 --pairs 1 "$noisy" -o "$work/aaf.exr" --progress none
        "$aaf" filter maaf6 "$noisy" -o "$work/maaf.exr" --progress none
        row="$effects,$width,$height,$spp,$reference_spp,$(rmse "$noisy" "$reference"),$(rmse "$work/aaf.exr" "$reference"),$(rmse "$work/maaf.exr" "$reference")"
        echo "$row" >>"$csv"
        echo "$row"
    done
done
mv "$csv" "$out/per_effect_${width}x$height.csv"
echo "wrote $out/per_effect_${width}x$height.csv"
