#!/usr/bin/env bash
# Filtering corrects a Cycles shot's own beauty (libaaf/RENDERERS.md "Blender"):
# a shot with a key light in the light group `key`, a second light and
# indirect light (tests/blender/cycles_two_lights_scene.py) is rendered by
# Cycles at 8 samples, completed with aaf's AOVs and filtered by
# `aaf filter aaf`: AAF filters Cycles' own pass of the key light
# (Combined_key) with its widths and swaps it into Combined, so
#  - outside the key light's penumbrae (where AAF's beta is 0) Combined is
#    Cycles' own, other light and indirect light included (RMSE below 1e-3);
#  - Combined is closer to Cycles' 1024-sample render than the noisy one is,
#    over the frame and inside the penumbrae.
# Usage: cycles_key_light_test.sh AAF_EXECUTABLE WORK_DIR
set -euo pipefail
aaf="$1" work="$2"
blender="${AAF_BLENDER:-$(command -v blender || true)}"
if [ -z "$blender" ]; then
  echo "SKIPPED: Blender is not installed (scripts/install_blender.sh installs Debian's Blender 3.4)"
  exit 77
fi
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
rm -rf "$work" && mkdir -p "$work"
"$blender" -b --factory-startup --python-exit-code 1 --python "$here/cycles_two_lights_scene.py" -- \
  "$work" "$aaf" 8 1024 > "$work/scene.log" 2>&1 || { cat "$work/scene.log"; echo "FAILED: the Cycles shot"; exit 1; }
"$aaf" filter aaf "$work/noisy.completed.exr" --light "$work/shot.light.json" -o "$work/filtered.exr" \
  --progress none 2> "$work/filter.log" || { cat "$work/filter.log"; echo "FAILED: aaf filter"; exit 1; }
if grep -q "left as rendered" "$work/filter.log"; then
  cat "$work/filter.log"; echo "FAILED: the key light's pass was not swapped in"; exit 1
fi
/usr/bin/python3 - "$work" <<'PY'
import sys
import numpy as np
import OpenImageIO as oiio

work = sys.argv[1]


def channels(path, names):
    image = oiio.ImageInput.open(path)
    spec = image.spec()
    pixels = image.read_image(oiio.FLOAT)
    image.close()
    return np.stack([pixels[:, :, list(spec.channelnames).index(n)] for n in names], -1)


rgb = ["ViewLayer.Combined." + c for c in "RGB"]
noisy = channels(f"{work}/noisy.exr", rgb)
filtered = channels(f"{work}/filtered.exr", rgb)
reference = channels(f"{work}/reference.exr", rgb)
penumbra = channels(f"{work}/filtered.exr", ["ViewLayer.aaf_beta.X"])[:, :, 0] > 0


def rmse(a, b, where=None):
    d = (a - b) if where is None else (a - b)[where]
    return float(np.sqrt(np.mean(d * d)))


outside = rmse(filtered, noisy, ~penumbra)
before, after = rmse(noisy, reference), rmse(filtered, reference)
before_p, after_p = rmse(noisy, reference, penumbra), rmse(filtered, reference, penumbra)
print(f"penumbrae {penumbra.mean():.3f} of the frame; outside them Combined vs Cycles' own: RMSE {outside:.2e}")
print(f"vs 1024 samples: noisy {before:.5f}, filtered {after:.5f}; in the penumbrae {before_p:.5f} -> {after_p:.5f}")
ok = penumbra.any() and (~penumbra).any() and outside < 1e-3 and after < before and after_p < before_p
if not ok:
    print("FAILED")
    sys.exit(1)
PY
