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
R,G,B is not copied: the Cycles Combined pass is the beauty. The light is
not in the header: filter with `--light OUT_SCENE.light.json`.
Runs with Debian's /usr/bin/python3 and its OpenImageIO module.
"""
import sys

import numpy as np
import OpenImageIO as oiio


def fail(message):
    print(f"aaf_complete.py: error: {message}", file=sys.stderr)
    sys.exit(3)


def read(path):
    image = oiio.ImageInput.open(path)
    if image is None:
        fail(f"{path}: {oiio.geterror()}")
    spec = image.spec()
    pixels = image.read_image(oiio.FLOAT)
    image.close()
    if pixels is None:
        fail(f"{path}: cannot read its pixels")
    return spec, pixels.reshape(spec.height, spec.width, spec.nchannels)


def main(args):
    if len(args) != 3:
        print(__doc__.strip().splitlines()[2].strip(), file=sys.stderr)
        sys.exit(2)
    cycles_path, aaf_path, out_path = args
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
             if n not in ("R", "G", "B", "A") and prefix + n not in names]
    spec = oiio.ImageSpec(cycles_spec)
    spec.nchannels = len(names) + len(added)
    spec.channelnames = tuple(names + [n for _, n in added])
    spec.set_format(oiio.FLOAT)
    spec.channelformats = ()
    spec.attribute("compression", "zip")
    pixels = np.concatenate([cycles, aaf[:, :, [i for i, _ in added]]], axis=2)
    out = oiio.ImageOutput.create(out_path)
    if out is None or not out.open(out_path, spec) or not out.write_image(pixels) or not out.close():
        fail(f"{out_path}: {oiio.geterror()}")
    print(f"aaf_complete.py: {out_path}: {len(added)} aaf channels added under '{prefix}'")


if __name__ == "__main__":
    main(sys.argv[1:])
