#!/usr/bin/python3
"""Plots a study CSV (scripts/study.sh) as RMSE vs average spp, one panel per
scene and one curve per sampling/filter pair (AAF Fig. 6(c)), and prints the
adaptive average spp and the equal-error sample reduction of AS+AF against
plain Monte Carlo (NAS+UF).

usage: plot_study.py STUDY.csv OUT.png
"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

STYLE = {
    ("NAS", "UF"): ("tab:purple", "NAS, UF (plain Monte Carlo)"),
    ("AS", "UF"): ("tab:cyan", "AS, UF"),
    ("NAS", "NAF"): ("tab:red", "NAS, NAF (best fixed width)"),
    ("AS", "NAF"): ("gold", "AS, NAF (best fixed width)"),
    ("NAS", "AF"): ("tab:green", "NAS, AF"),
    ("AS", "AF"): ("navy", "AS, AF (AAF)"),
}


def load(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def spp_for_error(curve, error):
    """Average spp at which a curve (sorted by spp) reaches `error`, by log-log
    interpolation; extrapolated from the last two points beyond its range."""
    points = sorted((float(r["avg_spp"]), float(r["rmse"])) for r in curve)
    for (s0, e0), (s1, e1) in zip(points, points[1:]):
        if e1 <= error <= e0:
            t = (math.log(error) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(s0) + t * (math.log(s1) - math.log(s0))), False
    (s0, e0), (s1, e1) = points[-2], points[-1]
    slope = (math.log(e1) - math.log(e0)) / (math.log(s1) - math.log(s0))
    return math.exp(math.log(s1) + (math.log(error) - math.log(e1)) / slope), True


def main():
    rows = load(sys.argv[1])
    scenes = sorted({r["scene"] for r in rows})
    fig, axes = plt.subplots(1, len(scenes), figsize=(6.5 * len(scenes), 5), squeeze=False)
    for ax, scene in zip(axes[0], scenes):
        for (sampling, filt), (colour, label) in STYLE.items():
            curve = sorted(
                (float(r["avg_spp"]), float(r["rmse"]))
                for r in rows
                if r["scene"] == scene and r["sampling"] == sampling and r["filter"] == filt
            )
            if curve:
                ax.plot(*zip(*curve), "o-", color=colour, label=label, markersize=4)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("average samples per pixel")
        ax.set_ylabel("RMSE vs reference")
        ax.set_title(scene)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)

        plain = [r for r in rows if r["scene"] == scene and r["sampling"] == "NAS" and r["filter"] == "UF"]
        for r in rows:
            if r["scene"] == scene and r["sampling"] == "AS" and r["filter"] == "AF":
                spp, extrapolated = spp_for_error(plain, float(r["rmse"]))
                print(
                    f"{scene}: AS+AF mu {float(r['setting']):g}: avg {float(r['avg_spp']):.1f} spp, "
                    f"RMSE {float(r['rmse']):.5f}; plain MC needs {spp:.0f} spp for that error "
                    f"({spp / float(r['avg_spp']):.1f}x{', extrapolated' if extrapolated else ''})"
                )
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=110)


if __name__ == "__main__":
    main()
