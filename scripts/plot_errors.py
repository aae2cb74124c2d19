#!/usr/bin/python3
"""Plots error against samples per pixel, one curve per method, from the
CSV (--csv) or JSON (--json) outputs of `aaf compare`. Each input file is one
method's results; the x value of a pair is its `spp` field (the test image's
mean spp over shaded pixels, which `aaf compare` reads from the image's AOVs).

usage: plot_errors.py OUT.png METHOD=RESULTS [METHOD=RESULTS ...] [--metric rmse]
example:
  aaf compare 'noisy.####.exr' 'ref.####.exr' --csv noisy.csv
  aaf compare 'aaf.####.exr' 'ref.####.exr' --csv aaf.csv
  scripts/plot_errors.py errors.png noisy=noisy.csv AAF=aaf.csv
"""
import argparse
import csv
import json
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def points(path, metric):
    """(spp, value) pairs of one results file, sorted by spp."""
    if path.endswith(".json"):
        with open(path) as f:
            data = json.load(f)
        rows = data["pairs"] if "pairs" in data else [data]
    else:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
    result = []
    for row in rows:
        spp, value = row.get("spp"), row.get(metric)
        if spp in (None, "") or value in (None, ""):
            continue
        spp, value = float(spp), float(value)
        if math.isfinite(spp) and math.isfinite(value):
            result.append((spp, value))
    if not result:
        raise SystemExit(f"plot_errors: {path}: no rows with both spp and {metric}")
    return sorted(result)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("output")
    parser.add_argument("methods", nargs="+", help="METHOD=RESULTS.csv|json")
    parser.add_argument("--metric", default="rmse")
    args = parser.parse_args()
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    for spec in args.methods:
        if "=" not in spec:
            raise SystemExit(f"plot_errors: expected METHOD=RESULTS, got '{spec}'")
        name, path = spec.split("=", 1)
        ax.plot(*zip(*points(path, args.metric)), "o-", label=name, markersize=4)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("samples per pixel")
    ax.set_ylabel(args.metric)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.output, dpi=110)


if __name__ == "__main__":
    main()
