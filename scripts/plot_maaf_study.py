#!/usr/bin/env python3
"""Plots the MAAF study (scripts/maaf_study.sh) and prints its summary.

Usage: plot_maaf_study.py STUDY.csv PLOT.png

For each scene and each MAAF spp the summary gives the average spp AAF with
adaptive sampling and its filter needs for the same RMSE, by linear
interpolation of log RMSE against log spp between the two measured AAF points
that bracket it (no fitted model; outside the measured range it says so), the
RMSE AAF reaches in the same wall-clock time (the same interpolation against
log time), and MAAF's time split into sampling, accumulation and filtering.
"""
import csv
import math
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt


def interpolate(points, x):
    """y at x on the piecewise-linear curve through points [(x, y)] sorted by x (log-log); None outside."""
    for (x0, y0), (x1, y1) in zip(points, points[1:]):
        if min(x0, x1) <= x <= max(x0, x1) and x0 != x1:
            t = (math.log(x) - math.log(x0)) / (math.log(x1) - math.log(x0))
            return math.exp(math.log(y0) + t * (math.log(y1) - math.log(y0)))
    return None


def main():
    rows = list(csv.DictReader(open(sys.argv[1])))
    by_scene = defaultdict(lambda: defaultdict(list))
    for r in rows:
        for key in ("setting", "avg_spp", "rmse", "sampling_s", "accumulation_s", "filter_s"):
            r[key] = float(r[key])
        r["total_s"] = r["sampling_s"] + r["accumulation_s"] + r["filter_s"]
        by_scene[r["scene"]][r["method"]].append(r)

    scenes = sorted(by_scene)
    fig, axes = plt.subplots(2, len(scenes), figsize=(5.5 * len(scenes), 8), squeeze=False)
    for column, scene in enumerate(scenes):
        # "MAAF" is the CLI default (k = 3); "MAAF k=1" the paper's widths.
        variants = sorted((m for m in by_scene[scene] if m.startswith("MAAF")), key=lambda m: (m != "MAAF", m))
        maafs = {m: sorted(by_scene[scene][m], key=lambda r: r["avg_spp"]) for m in variants}
        aaf = sorted(by_scene[scene]["AAF-AS"], key=lambda r: r["avg_spp"])
        ax = axes[0][column]
        ax.loglog([r["avg_spp"] for r in aaf], [r["rmse"] for r in aaf], "o-", label="AAF adaptive + filter (mu swept)")
        for m, maaf in maafs.items():
            label = "MAAF N = 3 (25 filters), k = 3 (default)" if m == "MAAF" else f"{m} (paper widths)"
            ax.loglog([r["avg_spp"] for r in maaf], [r["rmse"] for r in maaf], "s-", label=label)
        ax.set_title(scene)
        ax.set_xlabel("average spp")
        ax.set_ylabel("RMSE of the beauty")
        ax.legend()
        ax = axes[1][column]
        ax.loglog([r["total_s"] for r in aaf], [r["rmse"] for r in aaf], "o-", label="AAF adaptive + filter")
        for m, maaf in maafs.items():
            ax.loglog([r["total_s"] for r in maaf], [r["rmse"] for r in maaf], "s-", label=m)
        ax.set_xlabel("wall-clock s (sampling + accumulation + filter)")
        ax.set_ylabel("RMSE of the beauty")
        ax.legend()

        spp_curve = [(r["avg_spp"], r["rmse"]) for r in aaf]
        time_curve = sorted((r["total_s"], r["rmse"]) for r in aaf)
        # RMSE falls with spp: interpolate spp as a function of RMSE.
        rmse_curve = sorted((r["rmse"], r["avg_spp"]) for r in aaf)
        for r in (r for maaf in maafs.values() for r in maaf):
            spp = interpolate(rmse_curve, r["rmse"])
            equal_time = interpolate(time_curve, r["total_s"])
            quality = (f"AAF needs {spp:.1f} spp for RMSE {r['rmse']:.5f} ({spp / r['avg_spp']:.2f}x)"
                       if spp else f"RMSE {r['rmse']:.5f} lies outside AAF's measured range "
                                   f"[{min(y for _, y in spp_curve):.5f}, {max(y for _, y in spp_curve):.5f}]")
            timing = (f"in the same {r['total_s']:.2f} s AAF reaches RMSE {equal_time:.5f}"
                      if equal_time else f"{r['total_s']:.2f} s lies outside AAF's measured times")
            print(f"{scene}: {r['method']} {r['avg_spp']:.0f} spp: {quality}; {timing}; MAAF time: sampling "
                  f"{r['sampling_s']:.2f} s, accumulation {r['accumulation_s']:.2f} s, filter {r['filter_s']:.2f} s")
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=90)


if __name__ == "__main__":
    main()
