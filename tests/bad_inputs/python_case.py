#!/usr/bin/python3
"""Runs one bad-input case of the Python module `aaf` (run_bad_inputs.py,
"program": "python"): the code given as the only argument, with `aaf`, `np`
and a few small values defined (Y: an 8x8 float32 plane; RGB: an aaf.Aovs
with R, G, B). A refusal is one line on stderr as a user's script would show
it, `aaf.Error: ...` or `aaf.InputError: ...`, and the exit code the CLI
uses for it: 3 for aaf.InputError (a file), 2 for aaf.Error (an argument).
Anything else escapes with its traceback and exit 1, which the runner
reports as wrong."""
import sys

import numpy as np

import aaf

Y = np.zeros((8, 8), np.float32)
RGB = aaf.Aovs({"R": Y, "G": Y, "B": Y})

try:
    exec(compile(sys.argv[1], "<case>", "exec"), {"aaf": aaf, "np": np, "Y": Y, "RGB": RGB})
except aaf.InputError as e:
    print("aaf.InputError: %s" % " ".join(str(e).split()), file=sys.stderr)
    sys.exit(3)
except aaf.Error as e:
    print("aaf.Error: %s" % " ".join(str(e).split()), file=sys.stderr)
    sys.exit(2)
