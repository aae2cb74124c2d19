#!/usr/bin/env bash
# ISG Table 1 (Robison and Shirley 2009) for this implementation: builds and
# runs scripts/bench/bench_isg.cpp (1024x768 gallery, search x gather samples
# in {9, 25, 49, 81} for isg-shadow, isg-glossy, isg-dof, with the no-ISG
# baseline) and writes scripts/bench/results/isg_table1.{json,md}.
# THREADS (default: all) caps oneTBB's workers.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench="$root/build/scripts/bench/bench_isg"
[ -x "$bench" ] || "$root/scripts/build.sh"
out="$root/scripts/bench/results"
mkdir -p "$out"
"$bench" --benchmark_format=console --benchmark_out="$out/isg_table1.json" --benchmark_out_format=json "$@"
/usr/bin/python3 - "$out/isg_table1.json" "$out/isg_table1.md" <<'PY'
import json, sys
runs = json.load(open(sys.argv[1]))
context = runs["context"]
cells, baseline = {}, {}
for b in runs["benchmarks"]:
    args = dict(part.split(":") for part in b["name"].split("/")[1:] if ":" in part)
    effect = b["label"]
    cells[(effect, int(args["search"]), int(args["gather"]))] = b["isg_ms"]
    baseline.setdefault(effect, []).append(b["baseline_ms"])
counts = [9, 25, 49, 81]
with open(sys.argv[2], "w") as f:
    f.write(f"ISG Table 1 for libaaf: milliseconds per 1024x768 frame through filter_aovs(), "
            f"{context['num_cpus']} CPUs at {context['mhz_per_cpu']} MHz, {context['date']}, "
            "3 iterations each. Columns: parameter-search samples; rows: gather samples. "
            "Baseline: the same pass without ISG (gaussian --sigma 0: copy and compose), "
            "mean over the rows. Command: scripts/bench_isg.sh\n\n")
    for effect in ("isg-shadow", "isg-glossy", "isg-dof"):
        if effect not in baseline:
            continue
        base = sum(baseline[effect]) / len(baseline[effect])
        f.write(f"**{effect}**, baseline {base:.1f} ms\n\n| gather \\ search | " +
                " | ".join(map(str, counts)) + " |\n|" + " --- |" * (len(counts) + 1) + "\n")
        for g in counts:
            f.write(f"| {g} | " + " | ".join(f"{cells[(effect, s, g)]:.1f}" for s in counts) + " |\n")
        f.write("\n")
print(open(sys.argv[2]).read())
PY
