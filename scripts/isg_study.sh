#!/usr/bin/env bash
# ISG study (Robison and Shirley 2009) on the shipped `gallery` scene: each
# effect's RMSE and FLIP against its distribution-ray-traced reference, for the
# ISG filter (CLI defaults) and for the single-sample input it starts from;
# soft shadows also against AAF at 9 spp (ISG: one shadow ray per pixel).
# Writes scripts/isg_study/results/{isg_study.csv,isg_study.md,contact_hardening.png}.
# Settings (env): WIDTH=320 HEIGHT=240 REF_SPP=256 AAF_SPP=9; AAF_ISG_OUT picks the folder.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
aaf="${AAF:-$root/build/cli/aaf}"
"$root/scripts/deps.sh"  # the plots need python3-matplotlib
[ -x "$aaf" ] || "$root/scripts/build.sh"
out="${AAF_ISG_OUT:-$root/scripts/isg_study/results}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
W="${WIDTH:-320}" H="${HEIGHT:-240}" REF="${REF_SPP:-256}" AAF_SPP="${AAF_SPP:-9}"
size=(--width "$W" --height "$H")
scene="$root/testdata/scenes/gallery.json"

# The references: soft shadows (shadow.V, beauty) and glossy (glossy.*) at REF spp.
"$aaf" render "$scene" "${size[@]}" --spp "$REF" --seed 1 --aovs isg,aaf,depth -o "$work/ref.exr"
# ISG's inputs: one ray per pixel and effect (the 1-spp beauty is the stochastic baseline).
"$aaf" render "$scene" "${size[@]}" --spp 1 --seed 2 --aovs isg,aaf,depth -o "$work/one.exr"
# AAF at the same scene with 9 shadow rays per pixel.
"$aaf" render "$scene" "${size[@]}" --spp "$AAF_SPP" --seed 3 --aovs aaf -o "$work/aaf_in.exr"
# Depth of field: the gallery through a thin lens focused on the post.
/usr/bin/python3 "$root/scripts/scenes/gallery_lens.py" "$scene" "$work/gallery_lens.json"
"$aaf" render "$work/gallery_lens.json" "${size[@]}" --spp "$REF" --seed 1 --aovs isg,depth -o "$work/lens.exr"
"$aaf" render "$work/gallery_lens.json" "${size[@]}" --spp 1 --seed 2 --aovs isg,depth -o "$work/lens_one.exr"

"$aaf" filter isg-shadow "$work/one.exr" -o "$work/isg_shadow.exr"
"$aaf" filter aaf "$work/aaf_in.exr" -o "$work/aaf.exr"
"$aaf" filter aaf "$work/one.exr" -o "$work/aaf_one.exr"  # AAF at ISG's budget: one shadow ray
"$aaf" filter isg-glossy "$work/one.exr" -o "$work/isg_glossy.exr"
"$aaf" filter isg-dof "$work/lens.exr" -o "$work/isg_dof.exr"
# ISG Table 1's extremes: 9 and 81 samples in both the search and the gather.
for n in 9 81; do
  samples=(--search-samples "$n" --gather-samples "$n")
  "$aaf" filter isg-shadow "$work/one.exr" "${samples[@]}" -o "$work/isg_shadow_$n.exr"
  "$aaf" filter isg-glossy "$work/one.exr" "${samples[@]}" -o "$work/isg_glossy_$n.exr"
  "$aaf" filter isg-dof "$work/lens.exr" "${samples[@]}" -o "$work/isg_dof_$n.exr"
done
# One setting changed at a time from the defaults.
"$aaf" filter isg-shadow "$work/one.exr" --sigma 0.0001 -o "$work/isg_shadow_sigma_1e-4.exr"
"$aaf" filter isg-shadow "$work/one.exr" --sigma 0.01 -o "$work/isg_shadow_sigma_1e-2.exr"
"$aaf" filter isg-shadow "$work/one.exr" --light-shape disk -o "$work/isg_shadow_disk.exr"
"$aaf" filter isg-shadow "$work/one.exr" --pattern stratified -o "$work/isg_shadow_stratified.exr"
"$aaf" filter isg-glossy "$work/one.exr" --spatial-weight gaussian -o "$work/isg_glossy_gaussian.exr"

mkdir -p "$out"
/usr/bin/python3 "$root/scripts/isg_study/isg_study.py" "$aaf" "$work" "$out" \
  "scene=gallery ${W}x${H}, references ${REF} spp, AAF ${AAF_SPP} spp, ISG defaults"
