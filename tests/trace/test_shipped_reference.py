"""The shipped grids reference (testdata/references) is what the tracer renders.

Two independent 64 spp renders of the same view estimate the tracer's noise
per pixel (half the variance of their difference). Against the reference,
their mean must then differ by no more than its noise:
  - the image mean of each channel within 5 standard errors (a changed light,
    material or exposure moves it by far more);
  - the RMSE within 1.3x the renders' own noise plus the reference's (a moved
    object, a changed shadow or a wrong frame raises it far more).
Usage: test_shipped_reference.py AAF REFERENCE SCRATCH_DIR
"""
import os
import subprocess
import sys

import numpy as np
import OpenImageIO as oiio


def read_rgb(path):
    image = oiio.ImageInput.open(path)
    if image is None:
        sys.exit(f"{path}: cannot open: {oiio.geterror()}")
    spec = image.spec()
    names = list(spec.channelnames)
    pixels = image.read_image(0, 0, 0, spec.nchannels, "float")
    image.close()
    return np.stack([pixels[:, :, names.index(c)] for c in "RGB"], axis=-1).astype(np.float64)


def main():
    aaf, reference_path, scratch = sys.argv[1:4]
    os.makedirs(scratch, exist_ok=True)
    reference = read_rgb(reference_path)
    height, width, _ = reference.shape
    spp, reference_spp = 64, 4096
    renders = []
    for seed in (7, 8):
        path = os.path.join(scratch, f"grids_{seed}.exr")
        subprocess.run([aaf, "render", "grids", "-o", path, "--width", str(width), "--height", str(height),
                        "--spp", str(spp), "--seed", str(seed), "--progress", "none"],
                       check=True, stdout=subprocess.DEVNULL)
        renders.append(read_rgb(path))
    mean = (renders[0] + renders[1]) / 2
    # Per-pixel variance of one render, then of their mean and of the reference.
    render_variance = (renders[0] - renders[1]) ** 2 / 2
    mean_variance = render_variance / 2
    reference_variance = render_variance * spp / reference_spp
    pixels = height * width
    failures = []
    for c, name in enumerate("RGB"):
        difference = float(np.mean(mean[:, :, c]) - np.mean(reference[:, :, c]))
        standard_error = float(np.sqrt(np.sum(mean_variance[:, :, c] + reference_variance[:, :, c])) / pixels)
        print(f"{name}: mean difference {difference:.3g}, standard error {standard_error:.3g}")
        if abs(difference) > 5 * standard_error:
            failures.append(f"channel {name}: image mean differs by {difference:.3g}, "
                            f"{abs(difference) / standard_error:.1f} standard errors")
    rmse = float(np.sqrt(np.mean((mean - reference) ** 2)))
    noise = float(np.sqrt(np.mean(mean_variance + reference_variance)))
    print(f"RMSE {rmse:.4g} against the noise {noise:.4g} ({rmse / noise:.3f}x)")
    if rmse > 1.3 * noise:
        failures.append(f"RMSE {rmse:.4g} is {rmse / noise:.2f}x the noise {noise:.4g} (limit 1.3x)")
    if failures:
        print(f"{reference_path}: not what the tracer renders; re-render it as "
              "testdata/references/README.md says:\n  " + "\n  ".join(failures), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
