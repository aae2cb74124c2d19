#!/usr/bin/python3
"""RMSE of a maaf6 render's focal-plane pixels against their neighbours', per layer.

Usage: maaf6_focal_rmse.py NOISY.exr REFERENCE.exr MAAF.exr BASELINE.exr SPP

NOISY is `aaf render room --aovs maaf6 --spp SPP` (it has maaf6.spp, id.object and the
wedges), REFERENCE a converged render of the same scene, MAAF and BASELINE the outputs of
`aaf filter maaf6` and `aaf filter maaf6 --pairs 1` on NOISY. Focal-plane pixels are those
with extra samples (maaf6.spp > SPP), neighbours the other hit pixels within 3 px, as in
scripts/study/maaf6_study.cpp. Also counts the pixels where MAAF used its partition (its
layer differs from the baseline's) and their RMSE.
"""
import sys

import numpy as np
import OpenImageIO as oiio


def read(path):
    image = oiio.ImageInput.open(path)
    if image is None:
        sys.exit(f"maaf6_focal_rmse: cannot read {path}")
    names = image.spec().channelnames
    pixels = image.read_image(oiio.FLOAT)
    image.close()
    return {name: pixels[:, :, i] for i, name in enumerate(names)}


def rmse(image, reference, prefix, mask):
    if not mask.any():
        return 0.0
    error = sum((image[prefix + c] - reference[prefix + c]) ** 2 for c in "RGB")
    return float(np.sqrt(error[mask].mean() / 3))


def main():
    if len(sys.argv) != 6:
        sys.exit(__doc__)
    noisy, reference, maaf, baseline = (read(p) for p in sys.argv[1:5])
    spp = int(sys.argv[5])
    focal = noisy["maaf6.spp"] > spp
    height, width = focal.shape
    near = np.zeros_like(focal)
    for dy in range(-3, 4):
        for dx in range(-3, 4):
            shifted = np.zeros_like(focal)
            shifted[max(0, -dy):height + min(0, -dy), max(0, -dx):width + min(0, -dx)] = \
                focal[max(0, dy):height + min(0, dy), max(0, dx):width + min(0, dx)]
            near |= shifted
    near &= ~focal & (noisy["id.object"] != 0)
    print(f"focal-plane pixels {focal.sum()}, neighbours {near.sum()}")
    everywhere = np.ones_like(focal)
    for name, image in (("input", noisy), ("maaf", maaf), ("baseline", baseline)):
        for prefix in ("", "maaf6.direct.", "maaf6.indirect."):
            if prefix + "R" in image:
                print(f"{name:8s} {prefix or 'beauty':15s} all {rmse(image, reference, prefix, everywhere):.5f}  "
                      f"focal {rmse(image, reference, prefix, focal):.5f}  "
                      f"neighbours {rmse(image, reference, prefix, near):.5f}")
    for prefix in ("maaf6.direct.", "maaf6.indirect."):
        used = sum(np.abs(maaf[prefix + c] - baseline[prefix + c]) for c in "RGB") > 1e-7
        for label, mask in (("focal", focal), ("neighbours", near)):
            both = mask & used
            print(f"{prefix:15s} partition used on {both.sum()}/{mask.sum()} {label}: "
                  f"maaf {rmse(maaf, reference, prefix, both):.5f}, baseline {rmse(baseline, reference, prefix, both):.5f}")


if __name__ == "__main__":
    main()
