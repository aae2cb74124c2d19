#!/usr/bin/python3
"""MAAF Sec. 5 tables from `aaf analyze wedge`, and the Table 1 investigation.

Usage: scripts/study/wedge_tables.py [AAF_BINARY] [OUT_DIR]
       (defaults build/cli/aaf and scripts/study/wedge)

Writes, into OUT_DIR:
  table1_box.csv          Table 1: box coverage, mean over 50 random wedges (seed 1): numerical
                          (grid 1024), MAAF Eq. 16-18 from the geometry, MAAF Eq. 16-18 as printed, the paper's
  table2_gauss.csv        Table 2: Gaussian accuracy and coverage, the three named wedges and the
                          50-wedge mean, AAF, FSF, MAAF(3/5/7); MAAF with MAAF Eq. 10's mu_p and with 1
  grid_convergence.csv    coverage and accuracy against grid size for one wedge
  table1_distributions.csv  closed-form (MAAF Eq. 16-18) means under other wedge distributions
  table1_findings.txt     what those numbers say about the paper's Table 1
Needs only Debian's python3-numpy besides the binary. Deterministic.
"""
import csv
import json
import os
import subprocess
import sys

import numpy as np

AAF = sys.argv[1] if len(sys.argv) > 1 else "build/cli/aaf"
OUT = sys.argv[2] if len(sys.argv) > 2 else "scripts/study/wedge"
PAPER_TABLE1 = {"AAF": 0.097, "FSF": 0.5, "MAAF(3)": 0.197, "MAAF(5)": 0.275, "MAAF(7)": 0.401,
                "MAAF(25)": 0.677, "MAAF(75)": 0.876, "MAAF(125)": 0.943}
TABLE1_PAIRS = "2,3,4,13,38,63"  # MAAF(3), (5), (7), (25), (75), (125): 2N - 1 filters
NAMED_WEDGES = [(0.5, 0.8), (1.5, 2.0), (0.7, 2.2)]


def analyze(*args):
    command = [AAF, "analyze", "wedge", "--json", *args]
    print("+", " ".join(command), flush=True)
    return json.loads(subprocess.run(command, check=True, capture_output=True, text=True).stdout)


def write_csv(name, header, rows):
    with open(os.path.join(OUT, name), "w", newline="") as f:
        writer = csv.writer(f, lineterminator="\n")
        writer.writerow(header)
        writer.writerows(rows)


def table1():
    out = analyze("--random", "50", "--seed", "1", "--box", "--filters", TABLE1_PAIRS)
    write_csv("table1_box.csv",
              ["method", "coverage_numerical", "coverage_eq16_18", "coverage_eq16_18_as_printed", "paper"],
              [[m, f"{v['coverage']:.4f}", f"{v['coverage_eq16_18']:.4f}",
                f"{v['coverage_eq16_18_as_printed']:.4f}", PAPER_TABLE1[m]] for m, v in out.items()])


def table2():
    rows = []
    for weights, flags in (("MAAF Eq. 10", []), ("1 (--no-mu)", ["--no-mu"])):
        for s_min, s_max in NAMED_WEDGES:
            out = analyze("--smin", str(s_min), "--smax", str(s_max), "--gauss", "--filters", "2,3,4", *flags)
            rows += [[f"({s_min}, {s_max})", weights, m, f"{v['accuracy']:.4f}", f"{v['coverage']:.4f}"]
                     for m, v in out.items()]
        out = analyze("--random", "50", "--seed", "1", "--gauss", "--filters", "2,3,4", "--grid", "512", *flags)
        rows += [["mean of 50 (seed 1; grid 512)", weights, m, f"{v['accuracy']:.4f}", f"{v['coverage']:.4f}"]
                 for m, v in out.items()]
    write_csv("table2_gauss.csv", ["wedge", "MAAF mu_p", "method", "accuracy", "coverage"], rows)


def convergence():
    rows = []
    for shape in ("--box", "--gauss"):
        for grid in (64, 128, 256, 512, 1024, 2048, 4096):
            out = analyze("--smin", "0.7", "--smax", "2.2", shape, "--filters", "3", "--grid", str(grid))
            for m in ("AAF", "FSF", "MAAF(5)"):
                rows.append([shape[2:], grid, m, f"{out[m]['coverage']:.7f}", f"{out[m]['accuracy']:.7f}",
                             f"{out[m]['coverage_eq16_18']:.7f}" if 'coverage_eq16_18' in out[m] else ""])
    write_csv("grid_convergence.csv", ["shape", "grid", "method", "coverage", "accuracy", "coverage_eq16_18"],
              rows)


def coverage(s_min, s_max, pairs, printed):
    """MAAF Eq. 18 (N = 1: MAAF Eq. 16): central term 1/s_min from the geometry, 1/s_min^2 as printed."""
    spread = 1 / s_min - 1 / s_max
    inv_s_avg = (1 / s_min + 1 / s_max) / 2
    central = 1 / s_min ** 2 if printed else 1 / s_min
    half = (pairs - 0.5) ** 2
    return 1 / (pairs * (pairs - 1) / half + (central + 2 * (pairs - 1) * inv_s_avg) / (spread * half))


def distributions(rng, count):
    a, b = rng.uniform(0, 10, count), rng.uniform(0, 10, count)
    yield "two uniform draws on (0 10) sorted [ours]", np.minimum(a, b), np.maximum(a, b)
    a = rng.uniform(0, 10, count)
    yield "s_min ~ U(0 10) then s_max ~ U(s_min 10)", a, rng.uniform(a, 10)
    b = rng.uniform(0, 10, count)
    yield "s_max ~ U(0 10) then s_min ~ U(0 s_max)", rng.uniform(0, b), b
    t1, t2 = rng.uniform(0, np.arctan(10), count), rng.uniform(0, np.arctan(10), count)
    yield "slope angles uniform on (0 atan 10) sorted", np.tan(np.minimum(t1, t2)), np.tan(np.maximum(t1, t2))
    l1, l2 = rng.uniform(np.log(0.01), np.log(10), count), rng.uniform(np.log(0.01), np.log(10), count)
    yield "log-uniform on (0.01 10) sorted", np.exp(np.minimum(l1, l2)), np.exp(np.maximum(l1, l2))
    a, b = rng.integers(1, 10, count), rng.integers(1, 10, count)
    keep = a != b
    yield "integers 1..9 sorted and unequal", np.minimum(a, b)[keep] * 1.0, np.maximum(a, b)[keep] * 1.0


def investigation():
    columns = {"AAF": 1, "MAAF(3)": 2, "MAAF(5)": 3, "MAAF(7)": 4, "MAAF(25)": 13, "MAAF(75)": 38, "MAAF(125)": 63}
    rng = np.random.default_rng(2017)
    rows = [["paper Table 1", "-"] + [PAPER_TABLE1[m] for m in columns] + ["-"]]
    for name, s_min, s_max in distributions(rng, 400000):
        for printed in (False, True):
            means = [np.mean(coverage(s_min, s_max, n, printed)) for n in columns.values()]
            errs = [np.std(coverage(s_min, s_max, n, printed)) / np.sqrt(50) for n in columns.values()]
            rms = np.sqrt(np.mean((np.array(means) - np.array([PAPER_TABLE1[m] for m in columns])) ** 2))
            rows.append([name, "as printed" if printed else "geometry"] + [f"{x:.3f}" for x in means] + [f"{rms:.3f}"])
            rows.append(["  +- one standard error of a 50-wedge mean", ""] + [f"{x:.3f}" for x in errs] + [""])
    write_csv("table1_distributions.csv", ["distribution", "MAAF Eq. 16-18"] + list(columns) + ["rms vs paper"], rows)

    # Increments between the MAAF(3), (5), (7) columns, per wedge, over a fine grid of 0 < s_min < s_max < 10.
    g = np.linspace(0.001, 9.999, 2500)
    s_min, s_max = np.meshgrid(g, g)
    keep = s_min < s_max
    s_min, s_max = s_min[keep], s_max[keep]
    lines = []
    for printed in (False, True):
        c3, c5, c7 = (coverage(s_min, s_max, n, printed) for n in (2, 3, 4))
        excess = np.max((c7 - c5) - (c5 - c3))
        lines.append(f"MAAF Eq. 18 {'as printed' if printed else 'from the geometry'}: over every wedge with 0 < s_min < "
                     f"s_max < 10, (MAAF(7) - MAAF(5)) - (MAAF(5) - MAAF(3)) is at most {excess:+.2g}; so is its mean "
                     f"over any one set of wedges. The paper's columns give (0.401 - 0.275) - (0.275 - 0.197) = "
                     f"{(0.401 - 0.275) - (0.275 - 0.197):+.3f}.")
    n_uniform = 400000
    a, b = rng.uniform(0, 10, n_uniform), rng.uniform(0, 10, n_uniform)
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    lines.append(f"Sorted uniform pairs: AAF mean from the geometry {np.mean((1 - lo / hi) / 4):.4f} (exactly 1/8: "
                 f"s_min/s_max is uniform on (0,1)); as printed {np.mean(lo / 4 * (1 - lo / hi)):.4f} "
                 f"(exactly E[s_max] E[r(1-r)]/4 = (20/3)(1/6)/4 = 5/18).")
    with open(os.path.join(OUT, "table1_findings.txt"), "w") as f:
        f.write("\n".join(lines) + "\n")


def main():
    os.makedirs(OUT, exist_ok=True)
    table1()
    table2()
    convergence()
    investigation()


if __name__ == "__main__":
    main()
