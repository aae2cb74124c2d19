#!/usr/bin/python3
"""Turns bench_isg's JSON into ISG Table 1 as Markdown: isg_table1.py IN.json OUT.md"""
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
            f"{context['num_cpus']} CPUs at {context['mhz_per_cpu']} MHz, {context['date']}, load average "
            f"{', '.join(f'{x:.1f}' for x in context.get('load_avg', []))} at the start (a shared machine: "
            "other jobs were running, so single cells are noisy), "
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
