#!/usr/bin/env bash
# The main job on the built-in default scene: install, build, render `grids`
# at 640x480 with 9 spp, filter with AAF, render (or reuse) a 4096 spp
# reference, compare, and print a summary. Outputs go to out/.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/build.sh"
aaf="$root/build/cli/aaf"
out="$root/out"
mkdir -p "$out"

width=640 height=480 spp=9 ref_spp=4096 seed=1
now() { date +%s.%N; }
elapsed() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", b - a }'; }

t0=$(now)
"$aaf" render grids -o "$out/grids_noisy.exr" --width $width --height $height --spp $spp --seed $seed
t1=$(now)
"$aaf" filter aaf "$out/grids_noisy.exr" -o "$out/grids_aaf.exr"
t2=$(now)
# The reference depends only on the tracer's sources and the settings: reuse it while they are unchanged.
ref_key=$(cat "$root"/libaaf/trace/*.cpp "$root"/libaaf/trace/*.h "$root"/libaaf/trace/include/aaf/trace/*.h 2>/dev/null |
          sha1sum | cut -c1-10)
reference="$out/grids_ref_${ref_spp}spp_${width}x${height}_${ref_key}.exr"
ref_time="reused"
if [ ! -f "$reference" ]; then
  t3=$(now)
  "$aaf" render grids -o "$reference" --width $width --height $height --spp $ref_spp --seed 12345
  ref_time="$(elapsed "$t3" "$(now)") s"
fi
t4=$(now)
rmse_noisy=$("$aaf" compare "$out/grids_noisy.exr" "$reference" | awk '{print $2}')
rmse_aaf=$("$aaf" compare "$out/grids_aaf.exr" "$reference" | awk '{print $2}')
t5=$(now)
avg_spp=$("$aaf" info "$out/grids_noisy.exr" | awk '/^mean spp over shaded pixels/ {print $6}')

"$aaf" preview "$out/grids_noisy.exr" -o "$out/grids_noisy.png"
"$aaf" preview "$out/grids_aaf.exr" -o "$out/grids_aaf.png"
"$aaf" preview "$reference" -o "$out/grids_ref.png"
"$aaf" preview "$out/grids_aaf.exr" -o "$out/grids_beta.png" --channels aaf.beta --exposure 3

echo
echo "grids ${width}x${height}, AAF (mu 2, k 3, alpha 1), reference ${ref_spp} spp"
printf '%-28s %s\n' "avg spp" "$avg_spp"
printf '%-28s %s\n' "RMSE unfiltered" "$rmse_noisy"
printf '%-28s %s\n' "RMSE AAF filtered" "$rmse_aaf"
printf '%-28s %s\n' "error ratio (unfilt/filt)" "$(awk -v a="$rmse_noisy" -v b="$rmse_aaf" 'BEGIN { printf "%.2f", a / b }')"
printf '%-28s %s s\n' "time render ${spp} spp" "$(elapsed "$t0" "$t1")"
printf '%-28s %s s\n' "time AAF filter (w/ I/O)" "$(elapsed "$t1" "$t2")"
printf '%-28s %s\n' "time reference" "$ref_time"
printf '%-28s %s s\n' "time compare (2x)" "$(elapsed "$t4" "$t5")"
echo "images: $out/grids_{noisy,aaf,ref,beta}.png and .exr"
