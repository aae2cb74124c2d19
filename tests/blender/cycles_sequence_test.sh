#!/usr/bin/env bash
# A Cycles sequence filtered with a temporal window that follows Blender's
# own Vector pass (libaaf/AOV_CONTRACT.md: the motion role's Blender synonym,
# x negated): tests/blender/cycles_two_lights_scene.py renders 6 frames of
# the two-lights shot with the camera sliding sideways (8 samples, and 256
# for the references), completes each with aaf's AOVs but not aaf's motion
# layer, and `aaf filter aaf --temporal-window 2` filters them. Checks that
#  - the Vector pass, read in the contract's convention, takes each pixel's
#    surface point to where the previous frame's position layer has it
#    (closer than not moving it at all);
#  - no frame's Combined gets farther from its 256-sample render than when
#    filtered alone, and the frame-to-frame change of the error drops.
# Usage: cycles_sequence_test.sh AAF_EXECUTABLE WORK_DIR
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
  "$work" "$aaf" 8 256 6 > "$work/scene.log" 2>&1 || { cat "$work/scene.log"; echo "FAILED: the Cycles sequence"; exit 1; }
for mode in alone window; do
  window=()
  [ "$mode" = window ] && window=(--temporal-window 2)
  "$aaf" filter aaf "$work/noisy.completed.####.exr" --light "$work/shot.0001.light.json" --frames 1-6 \
    -o "$work/$mode.####.exr" --progress none "${window[@]}" 2> "$work/$mode.log" ||
    { cat "$work/$mode.log"; echo "FAILED: aaf filter ($mode)"; exit 1; }
done
/usr/bin/python3 - "$work" <<'PY'
import sys
import numpy as np
import OpenImageIO as oiio

work = sys.argv[1]
FRAMES = range(1, 7)


def read(path):
    image = oiio.ImageInput.open(path)
    spec = image.spec()
    pixels = image.read_image(oiio.FLOAT)
    image.close()
    return {name: pixels[:, :, i] for i, name in enumerate(spec.channelnames)}


completed = [read(f"{work}/noisy.completed.{f:04d}.exr") for f in FRAMES]
names = completed[0].keys()
if any(n.endswith("motion.X") for n in names) or "ViewLayer.Vector.X" not in names:
    print("FAILED: the completed frames should hold Blender's Vector pass and no aaf motion layer:", sorted(names))
    sys.exit(1)

# The convention: contract motion = (-Vector.X, Vector.Y), this frame minus the previous, pixels, y down.
height, width = completed[0]["ViewLayer.Vector.X"].shape
ys, xs = np.mgrid[0:height, 0:width]
moved, still = [], []
for previous, current in zip(completed, completed[1:]):
    mx, my = -current["ViewLayer.Vector.X"], current["ViewLayer.Vector.Y"]
    px = np.clip(np.rint(xs - mx).astype(int), 0, width - 1)
    py = np.clip(np.rint(ys - my).astype(int), 0, height - 1)
    position = [current[f"ViewLayer.P.{c}"] for c in "XYZ"]
    before = [previous[f"ViewLayer.P.{c}"] for c in "XYZ"]
    moved.append(np.median(np.sqrt(sum((p - b[py, px]) ** 2 for p, b in zip(position, before)))))
    still.append(np.median(np.sqrt(sum((p - b) ** 2 for p, b in zip(position, before)))))
print(f"median distance to the previous frame's surface point: following the Vector pass {np.mean(moved):.4f} m, "
      f"not moving {np.mean(still):.4f} m")

rgb = [f"ViewLayer.Combined.{c}" for c in "RGB"]


def beauty(path):
    channels = read(path)
    return np.stack([channels[n] for n in rgb], -1)


reference = [beauty(f"{work}/reference.{f:04d}.exr") for f in FRAMES]
errors = {}
for mode in ("alone", "window"):
    error = [beauty(f"{work}/{mode}.{f:04d}.exr") - r for f, r in zip(FRAMES, reference)]
    rmse = [float(np.sqrt(np.mean(e * e))) for e in error]
    temporal = float(np.mean([np.sqrt(np.mean((b - a) ** 2)) for a, b in zip(error, error[1:])]))
    errors[mode] = (rmse, temporal)
    print(mode, "RMSE per frame", " ".join(f"{v:.5f}" for v in rmse), f"temporal {temporal:.5f}")
(alone, alone_t), (window, window_t) = errors["alone"], errors["window"]
ok = np.mean(moved) < 0.5 * np.mean(still) and all(w <= a for a, w in zip(alone, window)) and window_t < alone_t
if not ok:
    print("FAILED")
    sys.exit(1)
PY
