#!/usr/bin/python3
"""maaf6 against its N = 1 control at equal time on room (scripts/maaf_control_study.sh).

For each spp S of --at: N = 3's whole time (render at S plus `aaf filter
maaf6`, each the whole process, median of 3) and its RMSE; N = 1 (`--pairs
1`) at the same samples, and at the samples S' its render plus its own
filter take in that time (the render's time fitted linear in spp), its RMSE
there interpolated (log-log) on its measured curve. Each N at its best k at
16 spp in control.csv, the bands at the render's (`--band-spp 0`), RMSE the
mean over the seeds. Appends a section to RESULTS.md in --out.
"""
import argparse
import csv
import math
import os
import statistics
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(__file__))
from control import beauty, common_arguments, run, split  # noqa: E402


def wall(cmd, repeats=3):
    times = []
    for _ in range(repeats):
        start = time.monotonic()
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
        times.append(time.monotonic() - start)
    return statistics.median(times)


def interpolate_loglog(points, x):
    points = sorted(points)
    if x <= points[0][0]:
        (x0, y0), (x1, y1) = points[0], points[1]
    elif x >= points[-1][0]:
        (x0, y0), (x1, y1) = points[-2], points[-1]
    else:
        i = next(i for i in range(1, len(points)) if points[i][0] >= x)
        (x0, y0), (x1, y1) = points[i - 1], points[i]
    t = (math.log(x) - math.log(x0)) / (math.log(x1) - math.log(x0))
    return math.exp(math.log(y0) + t * (math.log(y1) - math.log(y0)))


def main():
    ap = argparse.ArgumentParser()
    common_arguments(ap)
    ap.add_argument("--curve", default="9,16,24,32,48")
    ap.add_argument("--at", default="16,32")
    args = ap.parse_args()
    size = ["--width", str(args.width), "--height", str(args.height), "--progress", "none"]
    with open(f"{args.out}/control.csv") as f:
        rows = [r for r in csv.DictReader(f) if r["method"] == "maaf6" and r["scene"] == "room"]
    at16 = [r for r in rows if r["spp"] == "16"]
    k = {n: min((r for r in at16 if r["pairs"] == n), key=lambda r: float(r["rmse"]))["k"] for n in ("1", "3")}
    reference = beauty(f"{args.work}/maaf6.room.ref.exr")
    rmse, render_s, filter_s = {"1": [], "3": []}, [], {"1": {}, "3": {}}
    for spp in [int(s) for s in args.curve.split(",")]:
        inputs = []
        for seed in range(1, args.seeds + 1):
            path = f"{args.work}/maaf6.room.{spp}.{seed}.exr"
            if not os.path.exists(path):
                run([args.aaf, "render", "room", "--aovs", "maaf6", "--spp", str(spp), "--seed", str(seed),
                     "-o", path] + size)
            inputs.append(path)
        render_s.append((spp, wall([args.aaf, "render", "room", "--aovs", "maaf6", "--spp", str(spp), "--seed",
                                    "1", "-o", f"{args.work}/timing.exr"] + size)))
        for n, pairs in (("1", "1"), ("3", "all")):
            filter_cmd = [args.aaf, "filter", "maaf6", inputs[0], "--pairs", pairs, "--k", k[n], "--band-spp", "0",
                          "--progress", "none", "-o", f"{args.work}/timing_f.exr"]
            filter_s[n][spp] = wall(filter_cmd)
            filtered = []
            for i, path in enumerate(inputs):
                out = f"{args.work}/f.{i}.exr"
                run(filter_cmd[:3] + [path] + filter_cmd[4:-1] + [out])
                filtered.append(beauty(out))
            rmse[n].append((spp, split(filtered, reference)[0]))
        print(f"room {spp} spp: render {render_s[-1][1]:.2f} s, filter N=1 {filter_s['1'][spp]:.2f} s, "
              f"N=3 {filter_s['3'][spp]:.2f} s; rmse N=1 {rmse['1'][-1][1]:.5f}, N=3 {rmse['3'][-1][1]:.5f}",
              flush=True)
    # The render's time, linear in spp (least squares).
    xs, ys = [s for s, _ in render_s], [t for _, t in render_s]
    mx, my = statistics.mean(xs), statistics.mean(ys)
    slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
    intercept = my - slope * mx
    lines = ["", "## At equal time (room)", "",
             f"`scripts/maaf_control/equal_time.py`, {args.width}x{args.height}, seeds 1-{args.seeds}: N = 3 at "
             f"k = {k['3']} and N = 1 at k = {k['1']} (each one's best at 16 spp above), `--band-spp 0`. Times are "
             f"whole processes (`aaf render room --aovs maaf6`, then `aaf filter maaf6`), medians of 3, 2 threads; "
             f"the render takes {intercept:.2f} s + {1000 * slope:.1f} ms per spp (fitted over "
             f"{args.curve} spp). N = 1's RMSE at S' is interpolated log-log on its curve at those spp.", "",
             "| spp | N = 3: time (s) | RMSE | N = 1 at equal samples: RMSE | N = 1 at equal time: spp S' | RMSE |",
             "| --- | --- | --- | --- | --- | --- |"]
    curve1 = rmse["1"]
    for spp in [int(s) for s in args.at.split(",")]:
        render = intercept + slope * spp
        total = render + filter_s["3"][spp]
        n1_spp = (total - filter_s["1"][spp] - intercept) / slope
        lines.append(f"| {spp} | {total:.2f} | {dict(rmse['3'])[spp]:.5f} | {dict(curve1)[spp]:.5f} | "
                     f"{n1_spp:.1f} | {interpolate_loglog(curve1, n1_spp):.5f} |")
    with open(f"{args.out}/RESULTS.md", "a") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
