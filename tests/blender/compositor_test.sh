#!/usr/bin/env bash
# A real client reads aaf's output: Blender 3.4 opens a filtered EXR in its
# compositor, the filtered layers must appear as passes with the expected
# names, and the pixels Blender composites from them must equal aaf's.
# Usage: compositor_test.sh AAF_EXECUTABLE WORK_DIR
# Exits 77 (ctest: skipped) when Blender is not installed.
set -euo pipefail
aaf="$1" work="$2"
blender="${AAF_BLENDER:-$(command -v blender || true)}"
if [ -z "$blender" ]; then
  echo "SKIPPED: Blender is not installed (scripts/install_blender.sh installs Debian's Blender 3.4)"
  exit 77
fi
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
rm -rf "$work" && mkdir -p "$work"
"$aaf" render grids -o "$work/noisy.exr" --width 32 --height 24 --spp 4
"$aaf" filter aaf "$work/noisy.exr" -o "$work/filtered.exr"

# Combined = the filtered beauty R,G,B; aaf = the filtered visibility (Blender
# shows a layer of single channels as a value pass); aaf_beta = AAF's beta;
# noisy = the input beauty.
"$blender" -b --factory-startup --python "$here/check_compositor.py" -- \
  "$work/filtered.exr" "$work" "Combined,aaf,aaf_beta,noisy,shadow,unshadowed,P,N" 32 24 2>&1 | grep "aaf-check" || true
for pass in Combined aaf aaf_beta noisy; do
  [ -f "$work/blender_$pass.exr" ] || { echo "FAILED: Blender wrote no image for pass $pass"; exit 1; }
done
oiiotool "$work/filtered.exr" --ch "R=aaf.V,G=aaf.V,B=aaf.V" -o "$work/aaf_V.exr"
oiiotool "$work/filtered.exr" --ch "R=noisy.R,G=noisy.G,B=noisy.B" -o "$work/noisy_rgb.exr"
oiiotool "$work/filtered.exr" --ch "R=aaf_beta.X,G=aaf_beta.X,B=aaf_beta.X" -o "$work/aaf_beta.exr"
"$aaf" compare "$work/blender_Combined.exr" "$work/filtered.exr" --channels R,G,B --fail-above rmse=1e-6
"$aaf" compare "$work/blender_aaf.exr" "$work/aaf_V.exr" --channels R,G,B --fail-above rmse=1e-6
"$aaf" compare "$work/blender_noisy.exr" "$work/noisy_rgb.exr" --channels R,G,B --fail-above rmse=1e-6
"$aaf" compare "$work/blender_aaf_beta.exr" "$work/aaf_beta.exr" --channels R,G,B --fail-above rmse=1e-6
echo "OK: Blender $("$blender" --version 2>/dev/null | head -1 | cut -d' ' -f2) composites the filtered layers with aaf's values"
