#!/usr/bin/python3
"""Every figure in the README's method chooser comes from a committed record.

Usage: test_chooser_figures.py SOURCE_DIR

Reads the table under "## Which method" in README.md. For each row, every
number in its quality column (settings such as "320x240" or "9 spp" aside)
must be, rounded half-up to the digits the README shows, one of the numbers
of that method's study record, and the time must be the method's
`method_ms` in a benchmark record of the date the README names. A figure retyped by hand, or a record rerun without
updating the README, fails here. Exits 1 listing every figure not found."""
import os
import re
import sys
from decimal import ROUND_HALF_UP, Decimal

source_dir = sys.argv[1]
# Each method's study record(s), as the README's links below the table name them.
study = {
    "aaf": ["scripts/study/RESULTS.md"],
    "maaf": ["scripts/study/RESULTS_MAAF.md"],
    "maaf6": ["scripts/study/RESULTS_MAAF6.md"],
    "isg-shadow": ["scripts/isg_study/RESULTS.md"],
    "isg-glossy": ["scripts/isg_study/RESULTS.md"],
    "isg-dof": ["scripts/isg_study/RESULTS.md"],
    "ratio": ["scripts/ratio_study/RESULTS.md"],
    "gaussian": [],
}
number = re.compile(r"(?<![\w.])\d+(?:\.\d+)?(?![\w.]*\d)")


def read(path):
    with open(os.path.join(source_dir, path)) as f:
        return f.read()


def rounds_to(figure, candidates):
    """Whether some candidate, rounded half-up to `figure`'s decimals, is `figure`."""
    exponent = Decimal(figure).as_tuple().exponent
    target = Decimal(figure)
    return any(Decimal(c).quantize(Decimal(1).scaleb(exponent), rounding=ROUND_HALF_UP) == target
               for c in candidates)


readme = read("README.md")
section = readme[readme.index("## Which method"):]
section = section[:section.index("\n## ", 4)]
lines = section.splitlines()
header = next((i for i, line in enumerate(lines) if line.startswith("| method |")), len(lines))
rows = []
for line in lines[header + 2:]:  # the table's rows, up to the first line that is not one
    if not line.startswith("| `"):
        break
    rows.append(line)
bench = re.search(r"benchmark suite of (\d{4}-\d{2}-\d{2})", section)
if not rows or not bench:
    sys.exit("README.md: no method chooser table, or it names no benchmark suite date")
bench_dir = os.path.join(source_dir, "scripts/bench/results")
suite = sorted(f for f in os.listdir(bench_dir) if f.startswith("suite_" + bench.group(1)))
if not suite:
    sys.exit(f"no benchmark record scripts/bench/results/suite_{bench.group(1)}*.md")
bench_text = "\n".join(read(os.path.join("scripts/bench/results", f)) for f in suite)

missing, checked = [], 0
for row in rows:
    cells = [c.strip() for c in row.strip("|").split("|")]
    method = cells[0].strip("`")
    if method not in study:
        missing.append(f"{method}: a method the test does not know; add its record")
        continue
    records = "\n".join(read(p) for p in study[method])
    candidates = number.findall(records)
    quality = re.sub(r"\d+x\d+|(?<![\d.])\d+ (?:spp|rays?)|N = \d+", "", cells[3])  # settings, not figures
    for figure in number.findall(quality):
        checked += 1
        if not rounds_to(figure, candidates):
            missing.append(f"{method}: quality figure {figure} is in none of {', '.join(study[method])}")
    time = re.fullmatch(r"(\d+(?:\.\d+)?) (ms|s)", cells[4])
    if time:
        checked += 1
        value, unit = time.groups()
        ms = re.findall(r"BM_MethodVsCopyBandwidth/" + re.escape(method) + r"/\S* .*method_ms=([\d.]+k?)", bench_text)
        # Google Benchmark writes counters of 1000 and more with a k suffix.
        in_ms = [Decimal(m[:-1]) * 1000 if m.endswith("k") else Decimal(m) for m in ms]
        in_unit = [str(m / 1000 if unit == "s" else m) for m in in_ms]
        if not rounds_to(value, in_unit):
            missing.append(f"{method}: time {cells[4]} is not its method_ms in {', '.join(suite)} ({ms})")
for line in missing:
    print("README.md method chooser: " + line)
print(f"{checked} figures checked, {len(missing)} not found in the records")
sys.exit(1 if missing else 0)
