#!/usr/bin/python3
"""Plots a study CSV (scripts/study.sh) as RMSE vs average spp, one panel per
scene and one curve per sampling/filter pair (AAF Fig. 6(c)), and prints the
study's tables: with the CLI defaults the adaptive average spp, the filtered
RMSE against the best of a fixed-mu sweep and the equal-error sample
reduction of AS+AF against plain Monte Carlo (NAS+UF); then the gain of each
default over the paper's reading.

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
    columns = min(3, len(scenes))
    rows_of_panels = (len(scenes) + columns - 1) // columns
    fig, axes = plt.subplots(rows_of_panels, columns, figsize=(6.5 * columns, 5 * rows_of_panels), squeeze=False)
    for ax, scene in zip(axes.flat, scenes):
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

    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=110)
    print_tables(rows, scenes)


def find(rows, scene, sampling, filt, setting=None):
    for r in rows:
        if (r["scene"], r["sampling"], r["filter"]) == (scene, sampling, filt) and (
            setting is None or float(r["setting"]) == setting
        ):
            return r
    return None


def reduction(rows, scene, row):
    """Equal-error sample reduction of `row` over plain Monte Carlo (NAS+UF),
    interpolating the measured plain-MC error curve."""
    plain = [r for r in rows if r["scene"] == scene and r["sampling"] == "NAS" and r["filter"] == "UF"]
    spp, extrapolated = spp_for_error(plain, float(row["rmse"]))
    return spp, spp / float(row["avg_spp"]), extrapolated


def print_tables(rows, scenes):
    """The study's tables (scripts/study/RESULTS.md): the CLI defaults first, then
    each departure from the paper switched back alone, then the paper's
    whole pipeline."""
    print("CLI defaults (aaf render --adaptive; aaf filter aaf):")
    print("| scene | AS avg spp | RMSE unfiltered | RMSE AAF | best fixed mu (RMSE) | default / best "
          "| plain MC spp at that error | reduction |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    for scene in scenes:
        uf, af = find(rows, scene, "AS", "UF"), find(rows, scene, "AS", "AF")
        if af is None:
            continue
        sweep = [r for r in rows if (r["scene"], r["sampling"], r["filter"]) == (scene, "AS", "AF_fixed_mu")]
        best = min(sweep, key=lambda r: float(r["rmse"]))
        spp, ratio, extrapolated = reduction(rows, scene, af)
        print(f"| {scene} | {float(af['avg_spp']):.1f} | {float(uf['rmse']):.5f} | {float(af['rmse']):.5f} "
              f"| {float(best['setting']):g} ({float(best['rmse']):.5f}) "
              f"| {float(af['rmse']) / float(best['rmse']):.2f} | {spp:.0f}{' (extrapolated)' if extrapolated else ''} "
              f"| {ratio:.1f}x |")
    print()
    print("Filtered (AF, defaults) against unfiltered, every render of the study (plain spp values and adaptive):")
    for scene in scenes:
        worse = []
        pairs = 0
        for sampling in ("NAS", "AS"):
            for uf in [r for r in rows if (r["scene"], r["sampling"], r["filter"]) == (scene, sampling, "UF")]:
                af = find(rows, scene, sampling, "AF", float(uf["setting"]))
                if af is None:
                    continue
                pairs += 1
                ratio = float(af["rmse"]) / float(uf["rmse"])
                if ratio > 1:
                    worse.append(f"{sampling} {float(uf['setting']):g}: {ratio:.3f}")
        largest = max(float(find(rows, scene, s, "AF", float(u["setting"]))["rmse"]) / float(u["rmse"])
                      for s in ("NAS", "AS")
                      for u in rows if (u["scene"], u["sampling"], u["filter"]) == (scene, s, "UF"))
        print(f"- {scene}: {pairs} renders, AF/UF at most {largest:.3f}"
              + (f"; worse than unfiltered at {', '.join(worse)}" if worse else ", never worse"))
    print()
    print("Same adaptive render, one setting changed from the defaults (RMSE):")
    columns = [("AF", "defaults"), ("AF_bandlimit_equivalent_width", "band-limit equivalent width"),
               ("AF_bandlimit_spectrum", "band-limit spectrum"), ("AF_light_axes_shortest", "one band-limit (sharper axis)"),
               ("AF_pixel_projected", "projected pixel footprint"), ("AF_distance_plane", "distance: plane (Eq. 12)"),
               ("AF_distance_guarded", "distance: guarded plane"),
               ("AF_borders_clip", "one-sided borders"), ("AF_fixed_mu_default", "fixed mu 2 (paper)"),
               ("AF_paper", "paper's filter")]
    print("| scene | " + " | ".join(label for _, label in columns) + " |")
    print("| --- |" + " --- |" * len(columns))
    for scene in scenes:
        cells = []
        for filt, _ in columns:
            r = find(rows, scene, "AS", filt)
            cells.append(f"{float(r['rmse']):.5f}" if r else "-")
        print(f"| {scene} | " + " | ".join(cells) + " |")
    print()
    print("Self-occluded samples skipped (render --skip-self-occluded; default: an occluder at d2 = d1):")
    print("| scene | avg spp | RMSE AAF | filtered pixels | mean beta px | defaults: avg spp | RMSE AAF "
          "| filtered pixels | mean beta px |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for scene in scenes:
        so, af = find(rows, scene, "AS_skip_self_occluded", "AF"), find(rows, scene, "AS", "AF")
        if so is None or af is None:
            continue
        print(f"| {scene} | {float(so['avg_spp']):.1f} | {float(so['rmse']):.5f} | {float(so['filtered_share']):.3f} "
              f"| {float(so['mean_beta_px']):.2f} | {float(af['avg_spp']):.1f} | {float(af['rmse']):.5f} "
              f"| {float(af['filtered_share']):.3f} | {float(af['mean_beta_px']):.2f} |")
    print()
    print("The paper's pipeline (plan with 1/sigma and the receiver's footprint, as the defaults; filter as printed: "
          "fixed mu 2, 1/sigma, AAF Eq. 12's plane distances, one-sided borders, receiver pixel footprint) "
          "against the defaults:")
    print("| scene | paper: avg spp | RMSE unfiltered | RMSE AAF | reduction | defaults: avg spp | RMSE AAF "
          "| reduction |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    for scene in scenes:
        puf, paf = find(rows, scene, "AS_paper", "UF"), find(rows, scene, "AS_paper", "AF_paper")
        af = find(rows, scene, "AS", "AF")
        if paf is None or af is None:
            continue
        _, pratio, pext = reduction(rows, scene, paf)
        _, ratio, ext = reduction(rows, scene, af)
        print(f"| {scene} | {float(paf['avg_spp']):.1f} | {float(puf['rmse']):.5f} | {float(paf['rmse']):.5f} "
              f"| {pratio:.1f}x{'*' if pext else ''} | {float(af['avg_spp']):.1f} | {float(af['rmse']):.5f} "
              f"| {ratio:.1f}x{'*' if ext else ''} |")
    print("(* extrapolated beyond the measured plain-MC curve)")


if __name__ == "__main__":
    main()
