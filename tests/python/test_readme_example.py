#!/usr/bin/python3
"""Runs README.md's Python example as it stands there, after its shell lines,
and checks that the module's output holds the same pixels as `aaf filter`'s.

Usage: test_readme_example.py AAF_EXECUTABLE README.md SCRATCH_DIR
(PYTHONPATH must find the module `aaf`)."""
import os
import re
import shlex
import shutil
import subprocess
import sys

import numpy as np

aaf_exe, readme, scratch = (os.path.abspath(a) for a in sys.argv[1:4])
text = open(readme, encoding="utf-8").read()
# The example is the ```python block after the marker; its shell lines the
# last ```sh block before it (README "Quick start", "Python").
marker = text.index("<!-- python-example")
shell = re.findall(r"```sh\n(.*?)```", text[:marker], re.S)[-1]
python = re.search(r"<!-- python-example[^>]*-->\n```python\n(.*?)```", text[marker:], re.S).group(1)

shutil.rmtree(scratch, ignore_errors=True)
os.makedirs(scratch)
for line in shell.strip().splitlines():
    words = shlex.split(line, comments=True)
    assert words[0] == "aaf", line
    subprocess.run([aaf_exe] + words[1:], cwd=scratch, check=True)
subprocess.run([sys.executable, "-c", python], cwd=scratch, check=True)

import aaf  # noqa: E402  (after the example ran in its own interpreter)

cli = aaf.read(os.path.join(scratch, "filtered_cli.exr"))
py = aaf.read(os.path.join(scratch, "filtered_py.exr"))
assert list(cli.channels) == list(py.channels), (list(cli.channels), list(py.channels))
for name in cli.channels:
    assert np.array_equal(cli.channels[name], py.channels[name], equal_nan=True), name
# The filter changed the beauty (a copy of the input would also be "equal").
noisy = aaf.read(os.path.join(scratch, "noisy.exr"))
assert not np.array_equal(noisy.channels["R"], py.channels["R"])
print("README example: %d channels identical to aaf filter's" % len(cli.channels))
