#!/usr/bin/env bash
# The documentation's pictures: for each method, its scene's input, its
# filtered output and a converged reference side by side (a crop of a small
# render), and for AAF its filter widths and adaptive sample counts in false
# colour (AAF Fig. 7). Writes small PNGs beside each method's page,
# libaaf/core/methods/<name>/pictures/, which README.md and the pages show.
# Every method runs at its CLI defaults; the settings are the studies'
# (scripts/study, scripts/isg_study.sh, scripts/ratio_study.py) at a smaller size.
# About two minutes on 2 cores.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
aaf="${AAF:-$root/build/cli/aaf}"
[ -x "$aaf" ] || "$root/scripts/build.sh"
methods="$root/libaaf/core/methods"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
quiet=(--progress none)

# strip OUT CROP IMAGE:CHANNELS...: each image previewed (OCIO default view),
# cropped to CROP (WxH+X+Y) and laid side by side with a 2-pixel gap.
strip() {
  local out=$1 crop=$2 panels=() i=0
  shift 2
  for spec in "$@"; do
    local file=${spec%%:*} channels
    IFS=, read -ra channels <<< "${spec#*:}"
    "$aaf" preview "$file" --channels "${channels[@]}" -o "$work/panel_$i.png" > /dev/null
    oiiotool "$work/panel_$i.png" --cut "$crop" -o "$work/crop_$i.png"
    panels+=("$work/crop_$i.png")
    i=$((i + 1))
  done
  mkdir -p "$(dirname "$out")"
  oiiotool "${panels[@]}" --mosaic:pad=2 "${#panels[@]}x1" -d uint8 -o "$out"
  echo "wrote ${out#"$root"/}"
}

# AAF (grids): 9 spp, filtered, 1024 spp; then beta and the plan's spp.
"$aaf" render grids --width 320 --height 240 --spp 9 --seed 1 -o "$work/grids.exr" "${quiet[@]}"
"$aaf" render grids --width 320 --height 240 --spp 1024 --seed 1000 -o "$work/grids_ref.exr" "${quiet[@]}"
"$aaf" filter aaf "$work/grids.exr" -o "$work/grids_aaf.exr" "${quiet[@]}"
"$aaf" plan "$work/grids.exr" -o "$work/grids_plan.exr"
crop=160x120+80+60
strip "$methods/aaf/pictures/grids.png" $crop "$work/grids.exr:R,G,B" "$work/grids_aaf.exr:R,G,B" \
  "$work/grids_ref.exr:R,G,B"
"$aaf" preview "$work/grids_aaf.exr" --channels aaf_beta.X --false-colour -o "$work/beta.png" > /dev/null
"$aaf" preview "$work/grids_plan.exr" --channels plan.spp --false-colour -o "$work/spp.png" > /dev/null
oiiotool "$work/beta.png" "$work/spp.png" --mosaic:pad=2 2x1 -d uint8 -o "$methods/aaf/pictures/grids_beta_spp.png"
echo "wrote libaaf/core/methods/aaf/pictures/grids_beta_spp.png"

# AAF on a static sequence (grids, 9 spp, per-frame noise): the change of
# aaf.V from frame 4 to frame 5, x4 (the flicker a viewer sees), filtered
# frame by frame, then with --temporal-window 2.
"$aaf" render grids --width 320 --height 240 --spp 9 --frames 2-7 --aovs aaf,motion -o "$work/seq.####.exr" \
  "${quiet[@]}"
"$aaf" filter aaf "$work/seq.####.exr" -o "$work/alone.####.exr" --frames 4-5 "${quiet[@]}"
"$aaf" filter aaf "$work/seq.####.exr" -o "$work/window.####.exr" --frames 4-5 --temporal-window 2 "${quiet[@]}"
for mode in alone window; do
  oiiotool "$work/$mode.0005.exr" --ch aaf.V "$work/$mode.0004.exr" --ch aaf.V --sub --abs --mulc 4 \
    --cut 160x120+80+60 --ch 0,0,0 -o "$work/flicker_$mode.exr"
done
oiiotool "$work/flicker_alone.exr" "$work/flicker_window.exr" --mosaic:pad=2 2x1 -d uint8 \
  -o "$methods/aaf/pictures/grids_flicker.png"
echo "wrote libaaf/core/methods/aaf/pictures/grids_flicker.png"

# AAF on an animated sequence (testdata/sequences/crossing.json: a board's
# shadow sweeps over a box on a still camera), 9 spp: frames 3, 6, 9, 12 as
# columns (the lower part of the frame, twice the size); rows the input, each
# frame filtered alone, with --temporal-window 2, and a 256 spp reference.
# The window follows the motion layer: no ghost of the moving shadow.
crossing="$root/testdata/sequences/crossing.json"
"$aaf" render "$crossing" --width 128 --height 96 --spp 9 --frames 1-12 --aovs aaf,motion \
  -o "$work/cross.####.exr" "${quiet[@]}"
"$aaf" render "$crossing" --width 128 --height 96 --spp 256 --frames 3,6,9,12 --aovs aaf \
  -o "$work/cross_ref.####.exr" "${quiet[@]}"
"$aaf" filter aaf "$work/cross.####.exr" -o "$work/cross_alone.####.exr" --frames 1-12 "${quiet[@]}"
"$aaf" filter aaf "$work/cross.####.exr" -o "$work/cross_window.####.exr" --frames 1-12 \
  --temporal-window 2 "${quiet[@]}"
rows=()
for row in cross cross_alone cross_window cross_ref; do
  cells=()
  for frame in 0003 0006 0009 0012; do
    "$aaf" preview "$work/$row.$frame.exr" --channels R G B -o "$work/${row}_$frame.png" > /dev/null
    # The box's path through the shadow, twice the size.
    oiiotool "$work/${row}_$frame.png" --cut 96x48+16+48 --resize:filter=box 192x96 -o "$work/${row}_${frame}_cut.png"
    cells+=("$work/${row}_${frame}_cut.png")
  done
  oiiotool "${cells[@]}" --mosaic:pad=2 4x1 -o "$work/row_$row.png"
  rows+=("$work/row_$row.png")
done
oiiotool "${rows[@]}" --mosaic:pad=2 1x4 -d uint8 -o "$methods/aaf/pictures/crossing_strip.png"
echo "wrote libaaf/core/methods/aaf/pictures/crossing_strip.png"

# The gaussian baseline (grids): the same 9 spp, one screen-space width.
"$aaf" filter gaussian "$work/grids.exr" -o "$work/grids_gaussian.exr" "${quiet[@]}"
strip "$methods/gaussian/pictures/grids.png" 160x120+80+60 "$work/grids.exr:R,G,B" \
  "$work/grids_gaussian.exr:R,G,B" "$work/grids_ref.exr:R,G,B"

# MAAF (grids): 16 spp soft shadows, 25 filters in 4D, against AAF's 1024 spp reference.
"$aaf" render grids --width 320 --height 240 --spp 16 --seed 1 --aovs maaf -o "$work/grids_m.exr" "${quiet[@]}"
"$aaf" filter maaf "$work/grids_m.exr" -o "$work/grids_maaf.exr" "${quiet[@]}"
strip "$methods/maaf/pictures/grids.png" 160x120+80+60 "$work/grids_m.exr:R,G,B" "$work/grids_maaf.exr:R,G,B" \
  "$work/grids_ref.exr:R,G,B"

# MAAF 6D (room): 16 path samples, filtered, 256.
"$aaf" render room --width 160 --height 120 --spp 16 --seed 1 --aovs maaf6 -o "$work/room.exr" "${quiet[@]}"
"$aaf" render room --width 160 --height 120 --spp 256 --seed 1000 --aovs maaf6 -o "$work/room_ref.exr" "${quiet[@]}"
"$aaf" filter maaf6 "$work/room.exr" -o "$work/room_maaf6.exr" "${quiet[@]}"
strip "$methods/maaf6/pictures/room.png" 160x120+0+0 "$work/room.exr:R,G,B" "$work/room_maaf6.exr:R,G,B" \
  "$work/room_ref.exr:R,G,B"

# ISG (gallery): one ray per pixel and effect against distribution ray tracing.
"$aaf" render gallery --width 320 --height 240 --spp 1 --seed 2 --aovs isg,aaf,depth -o "$work/one.exr" "${quiet[@]}"
"$aaf" render gallery --width 320 --height 240 --spp 256 --seed 1 --aovs isg,aaf,depth -o "$work/ref.exr" "${quiet[@]}"
"$aaf" filter isg-shadow "$work/one.exr" -o "$work/isg_shadow.exr" "${quiet[@]}"
"$aaf" filter isg-glossy "$work/one.exr" -o "$work/isg_glossy.exr" "${quiet[@]}"
crop=200x120+60+100
strip "$methods/isg/pictures/gallery_shadow.png" $crop "$work/one.exr:isg.V" "$work/isg_shadow.exr:aaf.V" \
  "$work/ref.exr:shadow.V"
strip "$methods/isg/pictures/gallery_glossy.png" $crop "$work/one.exr:reflect.R,reflect.G,reflect.B" \
  "$work/isg_glossy.exr:isg_glossy.R,isg_glossy.G,isg_glossy.B" "$work/ref.exr:glossy.R,glossy.G,glossy.B"

# The ratio estimator (livingroom): 2 rays per light, denoised, 256.
"$aaf" render livingroom --width 160 --height 120 --spp 2 --seed 1 --aovs ratio -o "$work/lr.exr" "${quiet[@]}"
"$aaf" render livingroom --width 160 --height 120 --spp 256 --seed 1000 --aovs ratio -o "$work/lr_ref.exr" "${quiet[@]}"
"$aaf" filter ratio "$work/lr.exr" -o "$work/lr_ratio.exr" "${quiet[@]}"
strip "$methods/ratio/pictures/livingroom.png" 160x120+0+0 "$work/lr.exr:ratio.S.R,ratio.S.G,ratio.S.B" \
  "$work/lr_ratio.exr:R,G,B" "$work/lr_ref.exr:ratio.S.R,ratio.S.G,ratio.S.B"

# ISG depth of field (gallery through a thin lens focused on the post, as
# scripts/isg_study.sh): the pinhole image, isg-dof, the thin-lens reference.
/usr/bin/python3 "$root/scripts/scenes/gallery_lens.py" "$root/testdata/scenes/gallery.json" "$work/gallery_lens.json"
"$aaf" render "$work/gallery_lens.json" --width 160 --height 120 --spp 256 --seed 1 --aovs isg,depth -o "$work/lens.exr" \
  "${quiet[@]}"
"$aaf" filter isg-dof "$work/lens.exr" -o "$work/isg_dof.exr" "${quiet[@]}"
strip "$methods/isg/pictures/gallery_dof.png" 100x60+30+50 "$work/lens.exr:pinhole.R,pinhole.G,pinhole.B" \
  "$work/isg_dof.exr:isg_dof.R,isg_dof.G,isg_dof.B" "$work/lens.exr:R,G,B"
