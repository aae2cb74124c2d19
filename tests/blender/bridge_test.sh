#!/usr/bin/env bash
# The Blender bridge end to end (libaaf/RENDERERS.md "Blender"), with Debian's
# Blender 3.4 headless:
#  1. a shot built by script in Blender is exported (scripts/blender/aaf_bridge.py),
#     rendered by `aaf render --aovs all`, filtered by `aaf filter aaf`, and
#     opened in Blender's compositor: every filtered layer is a pass there,
#     pixel-identical to aaf's values;
#  2. the same shot rendered by Cycles: `aaf info` lists every missing input
#     at once; completed with the bridge's AOVs (aaf_complete.py) it filters
#     with --light in one run, its layers land under the Cycles file's view
#     layer, as Blender's compositor shows, and its Combined pass (no light
#     group of the key light to swap) stays Cycles' own, with a note.
# Usage: bridge_test.sh AAF_EXECUTABLE WORK_DIR
# Exits 77 (ctest: skipped) when Blender is not installed.
set -euo pipefail
aaf="$1" work="$2"
blender="${AAF_BLENDER:-$(command -v blender || true)}"
if [ -z "$blender" ]; then
  echo "SKIPPED: Blender is not installed (scripts/install_blender.sh installs Debian's Blender 3.4)"
  exit 77
fi
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
bridge="$here/../../scripts/blender"
rm -rf "$work" && mkdir -p "$work"
w=32 h=24
fail() { echo "FAILED: $*"; exit 1; }

"$blender" -b --factory-startup --python-exit-code 1 --python "$here/bridge_scene.py" -- \
  "$bridge" "$work" $w $h > "$work/scene.log" 2>&1 || { cat "$work/scene.log"; fail "building or exporting the shot"; }
grep "aaf-bridge-test" "$work/scene.log"

# 1. aaf's own render of the exported shot, filtered, in the compositor.
"$aaf" render "$work/shot.json" --width $w --height $h --spp 16 --aovs all -o "$work/aovs.exr" --progress none
"$aaf" filter aaf "$work/aovs.exr" -o "$work/filtered.exr"
"$blender" -b --factory-startup --python "$here/check_compositor.py" -- \
  "$work/filtered.exr" "$work" "Combined,aaf,aaf_beta,noisy" $w $h > "$work/compositor1.log" 2>&1 || true
grep "aaf-check" "$work/compositor1.log" || true
for pass in Combined aaf aaf_beta noisy; do
  [ -f "$work/blender_$pass.exr" ] || fail "Blender shows no pass $pass of aaf's filtered render"
done
check() {  # check BLENDER_IMAGE FILE R_CHANNEL G_CHANNEL B_CHANNEL
  "$aaf" compare "$1" "$2" --channels "R=$3,G=$4,B=$5" --fail-above rmse=0 > /dev/null \
    || fail "$1 differs from $2's $3,$4,$5"
}
check "$work/blender_Combined.exr" "$work/filtered.exr" R G B
check "$work/blender_aaf.exr" "$work/filtered.exr" aaf.V aaf.V aaf.V
check "$work/blender_aaf_beta.exr" "$work/filtered.exr" aaf_beta.X aaf_beta.X aaf_beta.X
check "$work/blender_noisy.exr" "$work/filtered.exr" noisy.R noisy.G noisy.B

# 2. The Cycles render of the same shot.
"$aaf" info "$work/cycles.exr" > "$work/info.txt"
for missing in "visibility \[ViewLayer.shadow.V\]" "d1 \[" "d2min \[" "d2max \[" "pixel_size \[" \
               "header aaf:light:center"; do
  grep -q "$missing" "$work/info.txt" || { cat "$work/info.txt"; fail "aaf info does not list $missing"; }
done
grep -q "^  aaf      missing" "$work/info.txt" || fail "aaf info calls the Cycles file ready for AAF"
/usr/bin/python3 "$bridge/aaf_complete.py" "$work/cycles.exr" "$work/aovs.exr" "$work/completed.exr"
"$aaf" filter aaf "$work/completed.exr" --light "$work/shot.light.json" -o "$work/cycles_filtered.exr"
rm -f "$work"/blender_*.exr
"$blender" -b --factory-startup --python "$here/check_compositor.py" -- \
  "$work/cycles_filtered.exr" "$work" "Combined,aaf,aaf_beta,noisy" $w $h > "$work/compositor2.log" 2>&1 || true
grep "aaf-check" "$work/compositor2.log" || true
for pass in Combined aaf aaf_beta noisy; do
  [ -f "$work/blender_$pass.exr" ] || fail "Blender shows no pass $pass of the filtered Cycles file"
done
L=ViewLayer
check "$work/blender_Combined.exr" "$work/cycles_filtered.exr" $L.Combined.R $L.Combined.G $L.Combined.B
check "$work/blender_noisy.exr" "$work/cycles.exr" $L.Combined.R $L.Combined.G $L.Combined.B
check "$work/blender_aaf.exr" "$work/cycles_filtered.exr" $L.aaf.V $L.aaf.V $L.aaf.V
check "$work/blender_aaf_beta.exr" "$work/cycles_filtered.exr" $L.aaf_beta.X $L.aaf_beta.X $L.aaf_beta.X
# This shot has no pass of the key light alone (no light group 'key'): its
# Combined stays Cycles' own, and the filter says so (the swap itself:
# cycles_key_light_test.sh).
"$aaf" compare "$work/cycles_filtered.exr" "$work/cycles.exr" --channels \
  "$L.Combined.R=$L.Combined.R,$L.Combined.G=$L.Combined.G,$L.Combined.B=$L.Combined.B" \
  --fail-above rmse=0 > /dev/null || fail "the Cycles file's Combined pass changed without a key light pass"
"$aaf" filter aaf "$work/completed.exr" --light "$work/shot.light.json" -o "$work/again.exr" \
  2> "$work/again.log" || fail "filtering the completed Cycles file again"
grep -q "R,G,B left as rendered" "$work/again.log" || fail "the filter does not say it kept the Cycles beauty"
echo "OK: exported, rendered, filtered and composited in Blender $("$blender" --version 2>/dev/null | head -1 | cut -d' ' -f2)"
