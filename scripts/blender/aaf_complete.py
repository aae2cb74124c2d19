#!/usr/bin/python3
"""Completes a Blender (Cycles) EXR with the AOVs only aaf's tracer writes.

  aaf_complete.py CYCLES.exr AAF_AOVS.exr OUT.exr

CYCLES.exr is a multilayer EXR Blender wrote (channels ViewLayer.Combined.R,
...); AAF_AOVS.exr is `aaf render` of the same shot exported by aaf_bridge.py
(`--aovs all`). OUT.exr is CYCLES.exr, header and channels unchanged, plus
every aaf channel it lacks (visibility, d1, d2min/d2max, pixel size,
unshadowed, spp, ...) under the Cycles file's view-layer prefix
(ViewLayer.shadow.V), where `aaf filter` finds them (the contract's names
under a view-layer prefix) and where its outputs then land. aaf's beauty
R,G,B and keylight.* (parts of aaf's own beauty) are not copied: the Cycles
Combined pass is the beauty, and its light group 'key' (Combined_key) the
key light's pass that `aaf filter aaf` filters and swaps into it. The light is
not in the header: filter with `--light OUT_SCENE.light.json`.
OUT.exr is written through a temporary file beside it and renamed into
place, so a failure leaves nothing behind; an OUT that is one of the inputs
(under any name) is refused. Exit codes are aaf's: 2 usage, 3 input/IO,
1 other.
Runs with Debian's /usr/bin/python3 and its OpenImageIO module.
"""
import os
import sys
import tempfile

import numpy as np
import OpenImageIO as oiio


def fail(message, code=3):
    """One error line (OpenImageIO's messages can span several) and aaf's exit code."""
    print("aaf_complete.py: error: " + " ".join(str(message).split()), file=sys.stderr)
    sys.exit(code)


def refuse_input_as_output(out_path, inputs):
    """An output that is an input, under any name (a symlink, a hard link,
    another spelling of the path), would be overwritten while it is read."""
    for path in inputs:
        same = os.path.realpath(out_path) == os.path.realpath(path)
        try:
            same = same or os.path.samefile(out_path, path)
        except OSError:  # either file missing: it cannot be the other one
            pass
        if same:
            fail(f"{out_path}: the output is the input {path}; write the completed file under another name")


def write_atomically(out_path, spec, pixels):
    """Writes through a temporary beside `out_path`, renamed into place."""
    folder = os.path.dirname(out_path) or "."
    try:
        handle, temporary = tempfile.mkstemp(dir=folder, prefix="." + os.path.basename(out_path) + ".",
                                             suffix=".tmp.exr")
    except OSError as e:
        fail(f"{out_path}: cannot write there: {e.strerror}")
    os.close(handle)
    try:
        out = oiio.ImageOutput.create(temporary)
        if out is None or not out.open(temporary, spec) or not out.write_image(pixels) or not out.close():
            fail(f"{out_path}: {oiio.geterror() or 'cannot write the image'}")
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(temporary, 0o666 & ~umask)  # mkstemp's 0600 is for the temporary only
        os.replace(temporary, out_path)
    except OSError as e:
        fail(f"{out_path}: cannot write it: {e.strerror}")
    finally:
        if os.path.exists(temporary):
            os.remove(temporary)


def read(path):
    image = oiio.ImageInput.open(path)
    if image is None:
        fail(f"{path}: {oiio.geterror() or 'cannot open it as an image'}")
    spec = image.spec()
    pixels = image.read_image(oiio.FLOAT)
    image.close()
    if pixels is None:
        fail(f"{path}: cannot read its pixels")
    return spec, pixels.reshape(spec.height, spec.width, spec.nchannels)


def main(args):
    if len(args) != 3:
        fail(f"expected 3 arguments, got {len(args)}; usage: {__doc__.strip().splitlines()[2].strip()}", 2)
    cycles_path, aaf_path, out_path = args
    if os.path.splitext(out_path)[1].lower() != ".exr":
        fail(f"{out_path}: the output is a multilayer OpenEXR; name it .exr", 2)
    if os.path.isdir(out_path):
        fail(f"{out_path}: is a folder")
    refuse_input_as_output(out_path, (cycles_path, aaf_path))
    cycles_spec, cycles = read(cycles_path)
    aaf_spec, aaf = read(aaf_path)
    names = list(cycles_spec.channelnames)
    combined = [n for n in names if n.endswith(".Combined.R")]
    if len(combined) != 1:
        fail(f"{cycles_path}: no single view layer with a Combined pass (channels {', '.join(names)})")
    prefix = combined[0][: -len("Combined.R")]
    if (aaf_spec.width, aaf_spec.height) != (cycles_spec.width, cycles_spec.height):
        fail(f"{aaf_path}: {aaf_spec.width}x{aaf_spec.height}, the Cycles file is "
             f"{cycles_spec.width}x{cycles_spec.height} (render both at the same size)")
    added = [(i, prefix + n) for i, n in enumerate(aaf_spec.channelnames)
             if n not in ("R", "G", "B", "A") and not n.startswith("keylight.") and prefix + n not in names]
    spec = oiio.ImageSpec(cycles_spec)
    spec.nchannels = len(names) + len(added)
    spec.channelnames = tuple(names + [n for _, n in added])
    spec.set_format(oiio.FLOAT)
    spec.channelformats = ()
    spec.attribute("compression", "zip")
    pixels = np.concatenate([cycles, aaf[:, :, [i for i, _ in added]]], axis=2)
    write_atomically(out_path, spec, pixels)
    print(f"aaf_complete.py: {out_path}: {len(added)} aaf channels added under '{prefix}'")


if __name__ == "__main__":
    try:
        main(sys.argv[1:])
    except Exception as e:  # a bug, not a bad input: still one line and a failing exit code
        fail(f"{type(e).__name__}: {e}", 1)
