#!/usr/bin/python3
"""The ratio estimator study (Heitz, Hill, McGuire 2018) on a multi-light
scene: RMSE and FLIP against a converged reference of the three estimators
with the same denoisers, the denoisers against each other, the error where
the reference is fully unshadowed, a one-at-a-time sweep of the bilateral's
parameters, and flicker on a static sequence with and without --temporal.

Run through scripts/ratio_study.sh, which names the settings; writes into
--out: ratio_study.csv, ratio_sweep.csv, ratio_flicker.csv, ratio_study.md
(the tables) and ratio_study.png (noisy / ratio / reference).
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import time

import numpy as np
import OpenImageIO as oiio

ESTIMATORS = ["ratio", "stochastic", "control-variate"]
DENOISERS = ["bilateral", "gaussian", "aaf"]


def run(cmd):
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)


def read_channels(path, names):
    image = oiio.ImageInput.open(path)
    if image is None:
        sys.exit(f"ratio_study: cannot read {path}")
    spec = image.spec()
    pixels = image.read_image(0, 0, 0, spec.nchannels, "float")
    image.close()
    index = {n: i for i, n in enumerate(spec.channelnames)}
    missing = [n for n in names if n not in index]
    if missing:
        sys.exit(f"ratio_study: {path} lacks {', '.join(missing)}")
    return np.stack([pixels[:, :, index[n]] for n in names], axis=-1)


def light_count(path):
    image = oiio.ImageInput.open(path)
    count = image.spec().getattribute("aaf:ratio:lights")
    image.close()
    return int(count or 0)


def write_rgb(path, rgb, prefix):
    spec = oiio.ImageSpec(rgb.shape[1], rgb.shape[0], 3, "float")
    spec.channelnames = tuple(prefix + c for c in "RGB")
    out = oiio.ImageOutput.create(path)
    out.open(path, spec)
    out.write_image(np.ascontiguousarray(rgb.astype(np.float32)))
    out.close()


def write_mask(path, mask):
    spec = oiio.ImageSpec(mask.shape[1], mask.shape[0], 1, "float")
    spec.channelnames = ("mask",)
    out = oiio.ImageOutput.create(path)
    out.open(path, spec)
    out.write_image(np.ascontiguousarray(mask[:, :, None].astype(np.float32)))
    out.close()


def erode(mask, radius):
    """True where every pixel of the (2 radius + 1)^2 square around is True (separable)."""
    out = mask.copy()
    for axis in (0, 1):
        padded = np.pad(out, [(radius, radius) if a == axis else (0, 0) for a in (0, 1)], constant_values=False)
        n = out.shape[axis]
        out = np.logical_and.reduce([np.take(padded, range(k, k + n), axis=axis) for k in range(2 * radius + 1)])
    return out


def ratio_limit(path):
    """What the ratio estimator converges to at this reference's samples:
    the sum over lights of U x S / U_N (W = 1 where U_N = 0), per channel."""
    lights = light_count(path)
    prefixes = [f"ratio.L{i}." for i in range(lights)] or ["ratio."]
    total = 0
    for p in prefixes:
        layers = read_channels(path, [p + l + "." + c for l in ("U", "S", "Un") for c in "RGB"])
        u, s, un = layers[..., 0:3], layers[..., 3:6], layers[..., 6:9]
        w = np.where(un > 0, np.clip(s / np.where(un > 0, un, 1), 0, 1), 1.0)
        total = total + u * w
    return total


def compare(aaf, test, reference, mask=None):
    cmd = [aaf, "compare", test, reference, "--metric", "rmse,flip", "--json",
           "--channels", "R=ratio.S.R,G=ratio.S.G,B=ratio.S.B"]
    if mask:
        cmd += ["--mask", mask]
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    result = json.loads(out)
    metrics = result.get("metrics", result)
    return float(metrics["rmse"]), float(metrics.get("flip", float("nan")))


def tonemap(rgb, exposure):
    return np.clip(rgb * exposure, 0, 1) ** (1 / 2.2)


def main():
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("--aaf", required=True)
    p.add_argument("--scene", default="livingroom")
    p.add_argument("--width", type=int, default=320)
    p.add_argument("--height", type=int, default=240)
    p.add_argument("--spp", default="1,2,4,8", help="shadow rays per light of the noisy renders")
    p.add_argument("--ref-spp", type=int, default=1024)
    p.add_argument("--sweep-spp", type=int, default=2)
    p.add_argument("--flicker-frames", type=int, default=6)
    p.add_argument("--out", required=True)
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    work = os.path.join(a.out, "work")
    os.makedirs(work, exist_ok=True)
    size = ["--width", str(a.width), "--height", str(a.height)]
    start = time.time()

    reference = os.path.join(work, "reference.exr")
    run([a.aaf, "render", a.scene, *size, "--spp", str(a.ref_spp), "--seed", "1000", "--aovs", "ratio",
         "-o", reference])
    ref = read_channels(reference, ["ratio.U.R", "ratio.U.G", "ratio.U.B", "ratio.S.R", "ratio.S.G", "ratio.S.B"])
    lum = np.array([0.2126, 0.7152, 0.0722])
    u_y, s_y = ref[..., :3] @ lum, ref[..., 3:] @ lum
    # Fully unshadowed: the converged S equals U (W = 1) on a lit surface.
    unshadowed = (u_y > 0) & (s_y >= 0.999 * u_y)
    mask = os.path.join(work, "unshadowed_mask.exr")
    write_mask(mask, unshadowed)
    # Its interior: at least 8 pixels from any pixel the reference shows shadowed.
    interior = erode(unshadowed | (u_y <= 0), 8) & unshadowed
    interior_mask = os.path.join(work, "interior_mask.exr")
    write_mask(interior_mask, interior)

    # The ratio estimator's own limit: U x S / U_N of the reference's samples;
    # its distance from the reference is the error of the analytic U (LTC's fit).
    limit = os.path.join(work, "limit.exr")
    write_rgb(limit, ratio_limit(reference), "ratio.S.")
    floor_rmse, floor_flip = compare(a.aaf, limit, reference)

    rows = []
    configs = [("noisy", "stochastic", "none", ["--denoiser", "gaussian", "--sigma", "0"]),
               ("ratio, not denoised", "ratio", "none", ["--denoiser", "gaussian", "--sigma", "0"])]
    for e in ESTIMATORS:
        for d in DENOISERS:
            configs.append((f"{e} / {d}", e, d, ["--denoiser", d]))
    configs.append(("ratio grey / bilateral", "ratio-grey", "bilateral", ["--grey"]))
    for n in [int(s) for s in a.spp.split(",")]:
        noisy = os.path.join(work, f"noisy_{n}.exr")
        run([a.aaf, "render", a.scene, *size, "--spp", str(n), "--seed", "1", "--aovs", "all,ratio", "-o", noisy])
        for label, estimator, denoiser, args in configs:
            out = os.path.join(work, "filtered.exr")
            run([a.aaf, "filter", "ratio", noisy, "-o", out, "--estimator",
                 "ratio" if estimator == "ratio-grey" else estimator, *args])
            rmse, flip = compare(a.aaf, out, reference)
            rmse_lit, _ = compare(a.aaf, out, reference, mask)
            rmse_interior, _ = compare(a.aaf, out, reference, interior_mask)
            rmse_limit, _ = compare(a.aaf, out, limit)
            rows.append({"spp_per_light": n, "configuration": label, "estimator": estimator,
                         "denoiser": denoiser, "rmse": rmse, "flip": flip, "rmse_unshadowed": rmse_lit,
                         "rmse_unshadowed_interior": rmse_interior, "rmse_vs_ratio_limit": rmse_limit})
            if n == 2 and label in ("noisy", "ratio / bilateral"):
                os.replace(out, os.path.join(work, f"picture_{'noisy' if label == 'noisy' else 'ratio'}.exr"))
    with open(os.path.join(a.out, "ratio_study.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)

    # One-at-a-time sweep of the bilateral's parameters around the defaults.
    sweep = []
    noisy = os.path.join(work, f"noisy_{a.sweep_spp}.exr")
    if not os.path.exists(noisy):
        run([a.aaf, "render", a.scene, *size, "--spp", str(a.sweep_spp), "--seed", "1", "--aovs", "all,ratio",
             "-o", noisy])
    grid = {"noise_radius": ["1", "2", "3", "4", "6", "8", "12"],
            "sigma_per_noise": ["0.5", "1", "2", "3", "4", "6", "8", "16", "24"],
            "max_sigma": ["2", "4", "8", "16"], "plane_sigma": ["0.5", "1", "2", "4"]}
    for name, values in grid.items():
        for value in values:
            out = os.path.join(work, "sweep.exr")
            run([a.aaf, "filter", "ratio", noisy, "-o", out, "--" + name.replace("_", "-"), value])
            rmse, flip = compare(a.aaf, out, reference)
            rmse_limit, _ = compare(a.aaf, out, limit)
            sweep.append({"spp_per_light": a.sweep_spp, "parameter": name, "value": value, "rmse": rmse,
                          "flip": flip, "rmse_vs_ratio_limit": rmse_limit})
    with open(os.path.join(a.out, "ratio_sweep.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(sweep[0].keys()))
        w.writeheader()
        w.writerows(sweep)

    # Flicker: a static camera, one render per frame with its own seed.
    flicker = []
    if a.flicker_frames > 1:
        for frame in range(1, a.flicker_frames + 1):
            run([a.aaf, "render", a.scene, *size, "--spp", str(a.sweep_spp), "--seed", str(100 + frame),
                 "--aovs", "all,ratio", "-o", os.path.join(work, f"seq.{frame:04d}.exr")])
        for temporal in (False, True):
            pattern = os.path.join(work, f"out_{int(temporal)}.####.exr")
            run([a.aaf, "filter", "ratio", os.path.join(work, "seq.####.exr"), "-o", pattern, "--progress", "none"]
                + (["--temporal"] if temporal else []))
            frames = [read_channels(pattern.replace("####", f"{f:04d}"), ["R", "G", "B"])
                      for f in range(1, a.flicker_frames + 1)]
            diffs = [np.sqrt(np.mean((frames[i] - frames[i - 1]) ** 2)) for i in range(1, len(frames))]
            errors = []
            for f in range(len(frames)):
                errors.append(np.sqrt(np.mean((frames[f] - ref[..., 3:]) ** 2)))
            flicker.append({"spp_per_light": a.sweep_spp, "temporal": temporal, "frames": a.flicker_frames,
                            "flicker_rmse_mean": float(np.mean(diffs)),
                            "flicker_rmse_last": float(diffs[-1]),
                            "rmse_last_frame": float(errors[-1])})
        with open(os.path.join(a.out, "ratio_flicker.csv"), "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(flicker[0].keys()))
            w.writeheader()
            w.writerows(flicker)

    # The picture: noisy (full stochastic) / ratio with the bilateral / reference, at 2 spp per light.
    panels = [read_channels(os.path.join(work, "picture_noisy.exr"), ["R", "G", "B"]),
              read_channels(os.path.join(work, "picture_ratio.exr"), ["R", "G", "B"]), ref[..., 3:]]
    exposure = 1.0 / max(np.percentile(s_y[s_y > 0], 99), 1e-6) if np.any(s_y > 0) else 1.0
    gap = np.ones((a.height, 4, 3))
    picture = np.concatenate([tonemap(panels[0], exposure), gap, tonemap(panels[1], exposure), gap,
                              tonemap(panels[2], exposure)], axis=1)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    plt.imsave(os.path.join(a.out, "ratio_study.png"), picture)

    with open(os.path.join(a.out, "ratio_study.md"), "w") as f:
        f.write(f"Scene `{a.scene}` at {a.width}x{a.height}; reference {a.ref_spp} samples per light "
                f"(seed 1000); noisy renders seed 1; `aaf filter ratio` defaults unless named. "
                f"RMSE and FLIP of R,G,B against the reference's ratio.S; 'unshadowed' = RMSE over the "
                f"{int(unshadowed.sum())} pixels whose reference S >= 0.999 U (luminance), 'interior' over the "
                f"{int(interior.sum())} of them at least 8 pixels from any shadowed pixel. 'limit' = the "
                f"ratio estimator's consistent limit at the reference's samples, sum over lights of "
                f"U x S / U_N: it differs from the reference by RMSE {floor_rmse:.5f} (FLIP {floor_flip:.4f}), "
                f"the error of the analytic U against the converged U_N, which no denoiser removes.\n\n")
        machine = subprocess.run([os.path.join(os.path.dirname(os.path.abspath(__file__)), "machine.sh")],
                                 capture_output=True, text=True, check=True).stdout.strip()
        f.write(f"Machine: {machine}.\n\n")
        spps = sorted({r["spp_per_light"] for r in rows})
        f.write("| configuration | " + " | ".join(f"RMSE {n} spp" for n in spps) + " | "
                + " | ".join(f"FLIP {n} spp" for n in spps) + " | " + " | ".join(f"unshadowed RMSE {n} spp" for n in spps)
                + " | " + " | ".join(f"interior RMSE {n} spp" for n in spps)
                + " | " + " | ".join(f"RMSE vs limit {n} spp" for n in spps) + " |\n")
        f.write("| --- |" + " --- |" * (5 * len(spps)) + "\n")
        for label, *_ in configs:
            by = {r["spp_per_light"]: r for r in rows if r["configuration"] == label}
            f.write(f"| {label} | " + " | ".join(f"{by[n]['rmse']:.5f}" for n in spps) + " | "
                    + " | ".join(f"{by[n]['flip']:.4f}" for n in spps) + " | "
                    + " | ".join(f"{by[n]['rmse_unshadowed']:.2e}" for n in spps) + " | "
                    + " | ".join(f"{by[n]['rmse_unshadowed_interior']:.2e}" for n in spps) + " | "
                    + " | ".join(f"{by[n]['rmse_vs_ratio_limit']:.5f}" for n in spps) + " |\n")
        f.write(f"\nSweep of one parameter at a time, {a.sweep_spp} samples per light, ratio / bilateral:\n\n")
        f.write("| parameter | value | RMSE | FLIP | RMSE vs the ratio's limit |\n| --- | --- | --- | --- | --- |\n")
        for r in sweep:
            f.write(f"| {r['parameter']} | {r['value']} | {r['rmse']:.5f} | {r['flip']:.4f} | "
                    f"{r['rmse_vs_ratio_limit']:.5f} |\n")
        if flicker:
            f.write(f"\nFlicker on a static camera, {a.flicker_frames} frames of {a.sweep_spp} samples per light "
                    "(seeds 101..), ratio / bilateral: mean frame-to-frame RMSE of R,G,B, and the last frame's RMSE "
                    "against the reference:\n\n| --temporal | flicker RMSE | last frame RMSE |\n| --- | --- | --- |\n")
            for r in flicker:
                f.write(f"| {'yes' if r['temporal'] else 'no'} | {r['flicker_rmse_mean']:.5f} | "
                        f"{r['rmse_last_frame']:.5f} |\n")
        f.write(f"\nWall time {time.time() - start:.0f} s.\n")


if __name__ == "__main__":
    main()
