#!/usr/bin/python3
"""Summary, plot and pictures of the MAAF 6D study (scripts/maaf_combined_study.sh).

Usage: plot_maaf6_study.py STUDY_DIR OUT_DIR
Reads STUDY_DIR/maaf6_study.csv and the EXRs beside it; writes OUT_DIR/summary.txt
(also printed), OUT_DIR/maaf6_rmse.png, OUT_DIR/maaf6_pictures.png and
OUT_DIR/maaf6_extra_spp.png. Equal-quality and equal-time AAF values are
interpolated between adjacent measured points of AAF's curve (log spp / log
RMSE, or time / RMSE), never from a fitted 1/sqrt(spp) law.
"""
import csv
import math
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import OpenImageIO as oiio


def read_rows(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for k in r:
            if k != "method":
                r[k] = float(r[k])
        r["total_s"] = r["sampling_s"] + r["prefilter_s"] + r["filter_s"]
    return rows


def interpolate(xs, ys, y_target, log_x=True):
    """x where the measured curve (x ascending, y falling) reaches y_target; None outside it."""
    for (x0, y0), (x1, y1) in zip(zip(xs, ys), zip(xs[1:], ys[1:])):
        if (y0 - y_target) * (y1 - y_target) <= 0 and y0 != y1:
            ly0, ly1, lt = math.log(y0), math.log(y1), math.log(y_target)
            t = (lt - ly0) / (ly1 - ly0)
            if log_x:
                return math.exp(math.log(x0) + t * (math.log(x1) - math.log(x0)))
            return x0 + t * (x1 - x0)
    return None


def value_at(xs, ys, x_target):
    """y of the measured curve at x_target by linear interpolation; None outside it."""
    for (x0, y0), (x1, y1) in zip(zip(xs, ys), zip(xs[1:], ys[1:])):
        if x0 <= x_target <= x1:
            t = (x_target - x0) / (x1 - x0) if x1 != x0 else 0.0
            return y0 + t * (y1 - y0)
    return None


def read_rgb(path):
    image = oiio.ImageBuf(path)
    spec = image.spec()
    pixels = image.get_pixels(oiio.FLOAT)
    names = list(spec.channelnames)
    return pixels, names


def tonemap(pixels, names):
    rgb = np.stack([pixels[:, :, names.index(c)] for c in "RGB"], axis=-1)
    return np.clip(rgb / (1 + rgb), 0, 1) ** (1 / 2.2)


def main():
    study, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    rows = read_rows(os.path.join(study, "maaf6_study.csv"))
    aaf = sorted([r for r in rows if r["method"] == "AAF"], key=lambda r: r["mean_spp"])
    maaf = sorted([r for r in rows if r["method"] == "MAAF"], key=lambda r: r["mean_spp"])
    noisy = sorted([r for r in rows if r["method"] == "input"], key=lambda r: r["mean_spp"])
    lines = []
    aaf_spp = [r["mean_spp"] for r in aaf]
    aaf_rmse = [r["rmse"] for r in aaf]
    aaf_time = [r["sampling_s"] + r["filter_s"] for r in aaf]
    for m in maaf:
        if m["spp"] not in (16, 32):
            continue
        eq_spp = interpolate(aaf_spp, aaf_rmse, m["rmse"])
        total = m["total_s"]
        line = (f"MAAF {int(m['spp'])} spp (mean {m['mean_spp']:.1f} with the focal-plane extra): RMSE {m['rmse']:.5f}; "
                f"sampling {m['sampling_s']:.2f} s, pre-filtering {m['prefilter_s']:.2f} s, filtering {m['filter_s']:.2f} s, "
                f"total {total:.2f} s.")
        if eq_spp is None:
            best = min(aaf, key=lambda r: r["rmse"])
            line += (f" Equal quality: AAF's measured curve does not reach this RMSE in {aaf_spp[0]:.1f}-{aaf_spp[-1]:.1f} "
                     f"mean spp (its best {best['rmse']:.5f} at {best['mean_spp']:.1f})." if m["rmse"] < min(aaf_rmse) else
                     f" Equal quality: AAF is already better at its fewest samples ({aaf_rmse[0]:.5f} at {aaf_spp[0]:.1f}).")
        else:
            eq_time = value_at(aaf_spp, aaf_time, eq_spp)
            line += (f" Equal quality: AAF needs {eq_spp:.1f} mean spp ({eq_spp / m['mean_spp']:.2f}x the samples), "
                     f"{eq_time:.2f} s: speedup {eq_time / total:.2f}x.")
        eq_rmse = value_at(aaf_time, aaf_rmse, total)
        if eq_rmse is not None:
            line += f" Equal time ({total:.2f} s): AAF RMSE {eq_rmse:.5f} ({eq_rmse / m['rmse']:.2f}x MAAF's)."
        else:
            line += f" Equal time: {total:.2f} s lies outside AAF's measured times {aaf_time[0]:.2f}-{aaf_time[-1]:.2f} s."
        line += (f" Focal-plane pixels (extra samples): RMSE {m['focal_rmse']:.5f} vs their neighbours' within 3 px "
                 f"{m['neighbour_rmse']:.5f}.")
        lines.append(line)
    for a in aaf:
        if a["spp"] in (16, 32):
            lines.append(f"AAF {int(a['spp'])} spp: RMSE {a['rmse']:.5f}, focal-plane {a['focal_rmse']:.5f} vs neighbours "
                         f"{a['neighbour_rmse']:.5f}; unfiltered input {[n['rmse'] for n in noisy if n['spp'] == a['spp']][0]:.5f}.")
    text = "\n".join(lines) + "\n"
    with open(os.path.join(out, "summary.txt"), "w") as f:
        f.write(text)
    print(text, end="")

    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for label, data, style in (("MAAF (N = 3)", maaf, "o-"), ("AAF (--pairs 1)", aaf, "s-"), ("unfiltered", noisy, "x:")):
        axes[0].loglog([r["mean_spp"] for r in data], [r["rmse"] for r in data], style, label=label)
        if label != "unfiltered":
            axes[1].loglog([r["sampling_s"] + r["prefilter_s"] + r["filter_s"] for r in data], [r["rmse"] for r in data],
                           style, label=label)
    axes[0].set_xlabel("mean path samples per pixel")
    axes[1].set_xlabel("seconds (sampling + pre-filtering + filtering)")
    for ax in axes:
        ax.set_ylabel("RMSE vs reference")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    fig.suptitle("room 320x240: soft shadows + defocus + indirect")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "maaf6_rmse.png"), dpi=100)

    def load(name):
        return tonemap(*read_rgb(os.path.join(study, name)))
    panels = [("reference", "reference.exr"), ("unfiltered 16 spp", "noisy_16.exr"), ("MAAF 16 spp", "maaf_16.exr"),
              ("AAF 16 spp", "aaf_16.exr"), ("MAAF 32 spp", "maaf_32.exr"), ("AAF 128 spp", "aaf_128.exr")]
    fig, axes = plt.subplots(2, 3, figsize=(12, 6.4))
    for ax, (title, name) in zip(axes.flat, panels):
        ax.imshow(load(name))
        ax.set_title(title)
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "maaf6_pictures.png"), dpi=90)

    pixels, names = read_rgb(os.path.join(study, "noisy_16.exr"))
    spp = pixels[:, :, names.index("maaf6.spp")]
    fig, ax = plt.subplots(figsize=(6, 4.6))
    shown = ax.imshow(spp - 16, cmap="magma")
    fig.colorbar(shown, ax=ax, label="extra path samples (focal-plane box)")
    ax.set_title("room, 16 spp: extra samples per pixel")
    ax.axis("off")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "maaf6_extra_spp.png"), dpi=90)


if __name__ == "__main__":
    main()
