#!/usr/bin/python3
"""Writes the bad-input corpus: testdata/bad/files/ (small crafted inputs) and
testdata/bad/cases.json (one case per command line, with the exit code and
error line the README promises). tests/bad_inputs/run_bad_inputs.py runs it.

Needs Debian's python3-openimageio and python3-numpy (scripts/deps.sh), hence
/usr/bin/python3 (TOOLCHAIN trap 4). Rerun after editing; the output is
deterministic (fixed seeds), so an unchanged script rewrites identical files.
"""
import json
import os
import shutil
import struct
import sys

import numpy as np
import OpenImageIO as oiio

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BAD = os.path.join(ROOT, "testdata", "bad")
FILES = os.path.join(BAD, "files")
FINDINGS = os.path.join(BAD, "fuzz_findings")  # inputs scripts/fuzz.sh found, kept as they were found
SIZE = 8  # every crafted image is 8x8: the corpus must run in seconds
FIXED_DATE = "2026:01:01 00:00:00"  # else OpenImageIO stamps the time and every rerun differs

# The AOVs `aaf filter aaf` reads (libaaf/AOV_CONTRACT.md), as a plausible
# soft shadow on a ground plane seen from above.
CHANNELS = ["R", "G", "B", "shadow.V", "shadow.d1", "shadow.d2min", "shadow.d2max",
            "P.X", "P.Y", "P.Z", "N.X", "N.Y", "N.Z", "id.object", "pixel.spp", "pixel.size",
            "unshadowed.R", "unshadowed.G", "unshadowed.B"]
LIGHT = {"aaf:light:center": (0.0, 3.0, 0.0), "aaf:light:normal": (0.0, -1.0, 0.0),
         "aaf:light:axis_u": (1.0, 0.0, 0.0), "aaf:light:axis_v": (0.0, 0.0, 1.0),
         "aaf:light:width_m": 1.0, "aaf:light:height_m": 1.0, "aaf:light:sigma_m": 0.5,
         "aaf:light:kind": "gaussian",
         # What the tracer's beauty holds, as aaf render writes it: a filter replaces exactly that.
         "aaf:beauty": "unshadowed*visibility+other_lights"}
RATIO_BEAUTY = dict(LIGHT, **{"aaf:beauty": "ratio.S"})


def path(name):
    return os.path.join(FILES, name)


def aov_planes(seed, size=SIZE):
    """Channel name -> size x size float plane."""
    rng = np.random.default_rng(seed)
    y, x = np.mgrid[0:size, 0:size].astype(np.float32)
    visibility = np.clip(x / (size - 1) + 0.2 * rng.standard_normal((size, size)), 0, 1).astype(np.float32)
    planes = {"shadow.V": visibility, "shadow.d1": np.full((size, size), 3.0, np.float32),
              "shadow.d2min": np.where(x > size / 2, 0.0, 1.5).astype(np.float32),
              "shadow.d2max": np.where(x > size / 2, 0.0, 2.0).astype(np.float32),
              "P.X": x * 0.1, "P.Y": np.zeros_like(x), "P.Z": y * 0.1,
              "N.X": np.zeros_like(x), "N.Y": np.ones_like(x), "N.Z": np.zeros_like(x),
              "id.object": np.ones_like(x), "pixel.spp": np.full_like(x, 9.0),
              "pixel.size": np.full_like(x, 0.1)}
    for c in "RGB":
        planes["unshadowed." + c] = np.full_like(x, 0.8)
        planes[c] = planes["unshadowed." + c] * visibility
    return planes


def write_exr(name, planes, attributes=LIGHT, size=SIZE, compression="zip"):
    names = list(planes)
    spec = oiio.ImageSpec(size, size, len(names), oiio.FLOAT)
    spec.channelnames = tuple(names)
    spec.attribute("compression", compression)
    spec.attribute("DateTime", FIXED_DATE)
    for key, value in attributes.items():
        if isinstance(value, tuple):
            spec.attribute(key, oiio.TypeDesc("float[3]"), value)
        else:
            spec.attribute(key, value)
    pixels = np.stack([planes[n] for n in names], axis=-1).astype(np.float32)
    out = oiio.ImageOutput.create(path(name))
    if not out.open(path(name), spec) or not out.write_image(pixels):
        sys.exit("cannot write %s: %s" % (name, oiio.geterror()))
    out.close()


def write_bytes(name, data):
    with open(path(name), "wb") as f:
        f.write(data)


def patch_box2i(name, source, attribute, xmax, ymax):
    """A copy of `source` whose header declares `attribute` (a box2i) as
    (0, 0)-(xmax, ymax): a huge declared size on a file of a few KB."""
    data = bytearray(open(path(source), "rb").read())
    key = attribute.encode() + b"\0box2i\0" + struct.pack("<i", 16)
    at = data.index(key) + len(key)
    data[at:at + 16] = struct.pack("<4i", 0, 0, xmax, ymax)
    write_bytes(name, bytes(data))


def exr_attribute(name, kind, value):
    return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(value)) + value


def write_declared_header(name, width, height, channels):
    """An EXR built byte by byte: a valid scan-line header declaring width x
    height float channels (ZIP, 16 lines per chunk), its offset table all
    zeros, and no pixel data: what a reader must refuse without allocating
    the declared size."""
    chlist = b"".join(c.encode() + b"\0" + struct.pack("<iB3xii", 2, 0, 1, 1) for c in channels) + b"\0"
    window = struct.pack("<4i", 0, 0, width - 1, height - 1)
    header = b"".join([
        exr_attribute("channels", "chlist", chlist),
        exr_attribute("compression", "compression", bytes([3])),
        exr_attribute("dataWindow", "box2i", window),
        exr_attribute("displayWindow", "box2i", window),
        exr_attribute("lineOrder", "lineOrder", bytes([0])),
        exr_attribute("pixelAspectRatio", "float", struct.pack("<f", 1.0)),
        exr_attribute("screenWindowCenter", "v2f", struct.pack("<2f", 0.0, 0.0)),
        exr_attribute("screenWindowWidth", "float", struct.pack("<f", 1.0)),
    ]) + b"\0"
    offsets = bytes(8 * ((height + 15) // 16))
    write_bytes(name, struct.pack("<Ii", 20000630, 2) + header + offsets)


def write_images():
    good = aov_planes(1)
    write_exr("good.exr", good)
    write_exr("good2.exr", aov_planes(2))
    write_exr("small.exr", aov_planes(3, size=4), size=4)
    write_exr("seq.0001.exr", good)
    write_exr("seq.0002.exr", aov_planes(4))
    write_exr("missing_visibility.exr", {k: v for k, v in good.items() if k != "shadow.V"})
    write_exr("missing_unshadowed.exr", {k: v for k, v in good.items() if not k.startswith("unshadowed")})
    write_exr("missing_light.exr", good, attributes={})
    write_exr("light_sigma_zero.exr", good, attributes={**LIGHT, "aaf:light:sigma_m": 0.0})
    write_exr("light_sigma_nan.exr", good, attributes={**LIGHT, "aaf:light:sigma_m": float("nan")})
    write_exr("light_normal_zero.exr", good, attributes={**LIGHT, "aaf:light:normal": (0.0, 0.0, 0.0)})
    write_exr("light_kind_bogus.exr", good, attributes={**LIGHT, "aaf:light:kind": "laser"})
    write_exr("raw_channel_name.exr", {**{k: v for k, v in good.items() if k != "shadow.V"},
                                       "bad\nname": good["shadow.V"]})
    mask = {"Y": np.ones((4, 4), np.float32)}
    write_exr("mask_small.exr", mask, attributes={}, size=4)
    whole = open(path("good.exr"), "rb").read()
    write_bytes("empty.exr", b"")
    write_bytes("garbage.exr", bytes(np.random.default_rng(7).integers(0, 256, 4096, dtype=np.uint8)))
    write_bytes("text.exr", b"this is not an image\n")
    write_bytes("truncated.exr", whole[:len(whole) // 2])
    write_bytes("truncated_header.exr", whole[:120])
    write_bytes("corrupt_data.exr", whole[:-300] + bytes(300))
    write_bytes("magic_only.exr", whole[:4])
    patch_box2i("huge_100000.exr", "good.exr", "dataWindow", 99999, 99999)
    write_declared_header("declared_100000.exr", 100000, 100000, sorted(CHANNELS))
    patch_box2i("declared_8000.exr", "good.exr", "dataWindow", 7999, 7999)
    write_exr("big.exr", {"Y": np.zeros((8000, 8000), np.float32)}, attributes={}, size=8000)
    big = open(path("big.exr"), "rb").read()
    os.remove(path("big.exr"))
    write_bytes("truncated_8000.exr", big[:60000])  # a real 8000x8000 header, 60 KB of its data
    png_spec = oiio.ImageSpec(SIZE, SIZE, 3, oiio.UINT8)
    png_spec.attribute("DateTime", FIXED_DATE)
    png = oiio.ImageBuf(png_spec)
    oiio.ImageBufAlgo.noise(png, "uniform", 0.0, 1.0, seed=5)  # so that a truncated copy lacks pixel data
    png.write(path("png_named.png"))
    os.replace(path("png_named.png"), path("png_named.exr"))
    write_bytes("png_truncated.exr", open(path("png_named.exr"), "rb").read()[:60])
    write_deep("deep.exr")
    for folder in ("folder.exr", "folder.png"):
        os.makedirs(path(folder), exist_ok=True)
        write_bytes(os.path.join(folder, "README"), b"a directory named like an image\n")
    write_bytes("stale_output.exr", whole[:200])


def write_deep(name):
    spec = oiio.ImageSpec(SIZE, SIZE, 2, oiio.FLOAT)
    spec.channelnames = ("Z", "A")
    spec.deep = True
    spec.attribute("DateTime", FIXED_DATE)
    buf = oiio.ImageBuf(spec)
    deep = buf.deepdata()
    for p in range(SIZE * SIZE):
        deep.set_samples(p, 1)
        deep.set_deep_value(p, 0, 0, 1.0)
        deep.set_deep_value(p, 1, 0, 1.0)
    if not buf.write(path(name)):
        sys.exit("cannot write %s: %s" % (name, buf.geterror()))


def scene(**overrides):
    """A tiny valid scene (libaaf/SCENE_FORMAT.md), with fields replaced."""
    base = {"format_version": 1, "name": "bad-input base",
            "camera": {"type": "pinhole", "position": [0, 3, 4], "look_at": [0, 0, 0], "fov_y_deg": 45},
            "lights": [{"center": [0, 3, 0], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1], "intensity": 10}],
            "objects": [{"type": "plane", "size": [4, 4], "id": 1},
                        {"type": "box", "min": [-0.3, 0.5, -0.3], "max": [0.3, 0.8, 0.3], "id": 2}]}
    base.update(overrides)
    return base


def write_scenes():
    def dump(name, value):
        write_bytes(name, json.dumps(value, indent=1).encode())

    base = scene()
    dump("scene.json", base)
    light = base["lights"][0]
    dump("light_far.json", scene(lights=[{**light, "center": [0, 1e20, 0]}]))
    dump("light_intensity_huge.json", scene(lights=[{**light, "intensity": 1e308}]))
    dump("light_edge_zero.json", scene(lights=[{**light, "edge_u": [0, 0, 0]}]))
    camera = {**base["camera"], "type": "thin_lens", "aperture_radius_m": 1e300}
    dump("aperture_huge.json", scene(camera=camera))
    dump("camera_same_points.json", scene(camera={**base["camera"], "look_at": [0, 3, 4]}))
    dump("fov_string.json", scene(camera={**base["camera"], "fov_y_deg": "wide"}))
    dump("no_lights.json", scene(lights=[]))
    dump("obj_missing.json", scene(objects=[{"type": "obj", "file": "nosuch.obj", "id": 1}]))
    dump("obj_bad_index.json", scene(objects=[{"type": "obj", "file": "bad_index.obj", "id": 1}]))
    dump("obj_garbage.json", scene(objects=[{"type": "obj", "file": "garbage.obj", "id": 1}]))
    dump("mesh_scene.json", scene(objects=[{"type": "obj", "file": "mesh.obj", "id": 1}]))
    dump("unknown_type.json", scene(objects=[{"type": "teapot", "id": 1}]))
    dump("scene_array.json", [1, 2, 3])
    write_bytes("huge_number.json", json.dumps(scene()).replace('"intensity": 10', '"intensity": 1e400').encode())
    write_bytes("truncated.json", json.dumps(scene()).encode()[:100])
    write_bytes("empty.json", b"")
    write_bytes("mesh.obj", b"v -1 0 -1\nv 1 0 -1\nv 0 0 1\nf 1 2 3\n")
    write_bytes("bad_index.obj", b"v -1 0 -1\nv 1 0 -1\nv 0 0 1\nf 1 2 9\n")
    write_bytes("garbage.obj", bytes(np.random.default_rng(8).integers(0, 256, 2048, dtype=np.uint8)))


def case(name, args, code, names=None, defect=None, **extra):
    """One command line. `names`: the file (or option) the single error line
    must name; `defect`: the issue item it reproduces (informative)."""
    entry = {"name": name, "args": args, "exit": code}
    if names:
        entry["names"] = names
    if defect:
        entry["defect"] = defect
    entry.update(extra)
    return entry


RENDER = ["render", "scene.json", "-o", "out.exr", "--width", "8", "--height", "8", "--spp", "1"]


def render_cases():
    def scene_case(name, scene_file, code=3, defect=None, **extra):
        return case(name, ["render", scene_file, "-o", "out.exr", "--width", "8", "--height", "8", "--spp", "1"],
                    code, names=scene_file, defect=defect, **extra)

    def option_case(name, option, value, defect=8):
        args = RENDER + [option, value] if value is not None else RENDER + [option]
        return case(name, args, 2, names=value if value and value.isalpha() else None, defect=defect)

    return [
        case("render output is the scene", RENDER[:3] + ["scene.json"] + RENDER[4:], 3, "scene.json", 1),
        case("render output is its OBJ", ["render", "mesh_scene.json", "-o", "mesh.obj", "--width", "8",
                                          "--height", "8", "--spp", "1"], 3, "mesh.obj", 1),
        scene_case("render missing scene file", "nosuch.json"),
        scene_case("render empty scene file", "empty.json"),
        scene_case("render truncated JSON", "truncated.json"),
        scene_case("render JSON number 1e400", "huge_number.json", defect=9),
        scene_case("render scene that is an array", "scene_array.json"),
        scene_case("render light centre 1e20", "light_far.json", defect=2),
        scene_case("render thin-lens aperture 1e300", "aperture_huge.json", defect=2),
        scene_case("render light intensity 1e308", "light_intensity_huge.json", defect=12),
        scene_case("render light with a zero edge", "light_edge_zero.json"),
        scene_case("render camera looking at itself", "camera_same_points.json"),
        scene_case("render field of view is a string", "fov_string.json"),
        scene_case("render scene without lights", "no_lights.json"),
        scene_case("render unknown object type", "unknown_type.json"),
        case("render OBJ missing", RENDER[:1] + ["obj_missing.json"] + RENDER[2:], 3, "nosuch.obj"),
        case("render OBJ face index out of range", RENDER[:1] + ["obj_bad_index.json"] + RENDER[2:], 3,
             "bad_index.obj"),
        case("render OBJ of random bytes", RENDER[:1] + ["obj_garbage.json"] + RENDER[2:], 3, "garbage.obj"),
        case("render into a folder", RENDER[:3] + ["folder.exr"] + RENDER[4:], 3, "folder.exr", 9),
        case("render into a missing folder", RENDER[:3] + ["nosuch/out.exr"] + RENDER[4:], 3, "nosuch/out.exr"),
        case("render under a file", RENDER[:3] + ["good.exr/out.exr"] + RENDER[4:], 3, "good.exr/out.exr"),
        option_case("render --spp 0", "--spp", "0"),
        option_case("render --width 0", "--width", "0"),
        option_case("render --height -8", "--height", "-8"),
        option_case("render --aovs bogus", "--aovs", "bogus"),
        case("render --adaptive --mu 0", RENDER + ["--adaptive", "--mu", "0"], 2, defect=8),
        case("render --adaptive --max-spp 0", RENDER + ["--adaptive", "--max-spp", "0"], 2, defect=8),
        option_case("render --light laser", "--light", "laser", defect=9),
        option_case("render --progress bogus", "--progress", "bogus"),
        option_case("render --checkpoint -1", "--checkpoint", "-1"),
        case("render --frames 3-1", RENDER[:3] + ["out.####.exr"] + RENDER[4:] + ["--frames", "3-1"], 2, defect=8),
        case("render --frames empty", RENDER[:3] + ["out.####.exr"] + RENDER[4:] + ["--frames", ""], 2, defect=12),
        case("render --frames 1-99999999999", RENDER[:3] + ["out.####.exr"] + RENDER[4:] +
             ["--frames", "1-99999999999"], 2, defect=9),
        case("render --frames 1-2000000000 --skip-existing on a missing scene",
             ["render", "nosuch.json", "-o", "out.####.exr", "--frames", "1-2000000000", "--skip-existing",
              "--width", "8", "--height", "8", "--spp", "1"], 3, "nosuch.json", 5),
        case("render --resume of garbage", RENDER + ["--resume", "garbage.exr"], 3, "garbage.exr"),
        case("render --resume of another size", RENDER + ["--resume", "small.exr"], 3, "small.exr"),
    ]


def filter_cases():
    def aaf(name, input_file, code=3, defect=None, names=None, extra_args=(), **extra):
        return case(name, ["filter", "aaf", input_file, "-o", "out.exr", *extra_args], code,
                    names or input_file, defect, **extra)

    def option(name, method, option, value, defect=8):
        named = value if value.replace("=", "").isalpha() else None
        return case(name, ["filter", method, "good.exr", "-o", "out.exr", option, value], 2, named, defect)

    return [
        aaf("filter aaf missing input", "nosuch.exr"),
        aaf("filter aaf zero-byte EXR", "empty.exr"),
        aaf("filter aaf garbage EXR", "garbage.exr"),
        aaf("filter aaf text named .exr", "text.exr"),
        aaf("filter aaf truncated EXR", "truncated.exr"),
        aaf("filter aaf truncated header", "truncated_header.exr"),
        aaf("filter aaf magic number only", "magic_only.exr"),
        aaf("filter aaf corrupt pixel data", "corrupt_data.exr"),
        aaf("filter aaf PNG named .exr", "png_named.exr", defect=9),
        aaf("filter aaf deep EXR", "deep.exr"),
        aaf("filter aaf header declares 100000x100000", "huge_100000.exr", defect=7),
        aaf("filter aaf 60 KB of an 8000x8000 file", "truncated_8000.exr", defect=7),
        aaf("filter aaf header alone declares 100000x100000", "declared_100000.exr", defect=7),
        aaf("filter aaf missing visibility", "missing_visibility.exr"),
        aaf("filter aaf missing light attributes", "missing_light.exr"),
        aaf("filter aaf light sigma 0", "light_sigma_zero.exr", defect=8),
        aaf("filter aaf light sigma NaN", "light_sigma_nan.exr", defect=8),
        aaf("filter aaf light normal zero", "light_normal_zero.exr", defect=8),
        aaf("filter aaf light kind unknown", "light_kind_bogus.exr", defect=8),
        aaf("filter aaf channel name with a line break", "raw_channel_name.exr", defect=9),
        aaf("filter aaf directory as input", "folder.exr"),
        case("filter aaf output is the input", ["filter", "aaf", "good.exr", "-o", "good.exr"], 3, "good.exr"),
        case("filter aaf output is a folder", ["filter", "aaf", "good.exr", "-o", "folder.exr"], 3,
             "folder.exr", 9),
        case("filter aaf output in a missing folder", ["filter", "aaf", "good.exr", "-o", "nosuch/out.exr"], 3,
             "nosuch/out.exr"),
        case("filter aaf output under a file", ["filter", "aaf", "good.exr", "-o", "good2.exr/out.exr"], 3,
             "good2.exr/out.exr"),
        option("filter aaf --mu 0", "aaf", "--mu", "0"),
        option("filter aaf --alpha 2", "aaf", "--alpha", "2"),
        option("filter aaf --k -1", "aaf", "--k", "-1"),
        option("filter aaf --normal-threshold 200", "aaf", "--normal-threshold", "200"),
        option("filter aaf --filter bogus", "aaf", "--filter", "bogus"),
        option("filter aaf --map nosuchrole=X", "aaf", "--map", "nosuchrole=X"),
        option("filter aaf --map visibility=", "aaf", "--map", "visibility="),
        option("filter aaf --compression bogus", "aaf", "--compression", "bogus", defect=9),
        option("filter aaf --threads -1", "aaf", "--threads", "-1"),
        case("filter aaf --frames 1-2000000000", ["filter", "aaf", "seq.####.exr", "-o", "out.####.exr",
                                                  "--frames", "3-2000000000", "--progress", "none"], 3,
             "seq.0003.exr", 5),
        case("filter aaf --frames abc", ["filter", "aaf", "seq.####.exr", "-o", "out.####.exr",
                                         "--frames", "abc"], 2, "abc"),
        case("filter aaf --frames 1-99999999999", ["filter", "aaf", "seq.####.exr", "-o", "out.####.exr",
                                                   "--frames", "1-99999999999"], 2, defect=9),
        case("filter aaf --skip-existing redoes a truncated output",
             ["filter", "aaf", "seq.####.exr", "-o", "out.####.exr", "--frames", "1", "--skip-existing",
              "--progress", "none"], 0, defect=6, setup={"copy": {"truncated.exr": "out.0001.exr"}},
             creates=["out.0001.exr"]),
        case("filter aaf removes its own stale temporary, not another program's",
             ["filter", "aaf", "good.exr", "-o", "out.exr"], 0, defect=10,
             setup={"copy": {"stale_output.exr": ".out.exr.tmp-999999-0",
                             "text.exr": ".out.exr.tmp-notours"}},
             creates=["out.exr"], removes=[".out.exr.tmp-999999-0"]),
        case("filter aaf writes an output name of 244 characters",
             ["filter", "aaf", "good.exr", "-o", "o" * 240 + ".exr"], 0, defect=10, creates=["o" * 240 + ".exr"]),
        case("filter gaussian missing visibility",
             ["filter", "gaussian", "missing_visibility.exr", "-o", "out.exr"], 3, "missing_visibility.exr"),
        case("filter gaussian missing unshadowed",
             ["filter", "gaussian", "missing_unshadowed.exr", "-o", "out.exr"], 3, "missing_unshadowed.exr"),
        case("filter gaussian garbage EXR", ["filter", "gaussian", "garbage.exr", "-o", "out.exr"], 3,
             "garbage.exr"),
        option("filter gaussian --sigma -1", "gaussian", "--sigma", "-1"),
        option("filter gaussian --sigma 1000", "gaussian", "--sigma", "1000"),
        case("filter unknown method", ["filter", "nosuch", "good.exr", "-o", "out.exr"], 2, "nosuch", 9),
    ]


def other_cases():
    def plan(name, input_file, code=3, defect=None, extra_args=()):
        return case(name, ["plan", input_file, "-o", "out.exr", *extra_args], code,
                    None if extra_args else input_file, defect)

    def compare(name, args, code, names=None, defect=None, **extra):
        return case(name, ["compare", *args], code, names, defect, **extra)

    def info(name, input_file, defect=None):
        return case(name, ["info", input_file], 3, input_file, defect)

    def preview(name, args, code, names=None, defect=None):
        return case(name, ["preview", *args], code, names, defect)

    return [
        plan("plan garbage EXR", "garbage.exr"),
        plan("plan missing light attributes", "missing_light.exr"),
        plan("plan light sigma 0", "light_sigma_zero.exr", defect=8),
        plan("plan --mu 0", "good.exr", 2, 8, ["--mu", "0"]),
        plan("plan --first-pass 0", "good.exr", 2, 8, ["--first-pass", "0"]),
        plan("plan --max-spp -5", "good.exr", 2, 8, ["--max-spp", "-5"]),
        case("plan output is the input", ["plan", "good.exr", "-o", "good.exr"], 3, "good.exr"),
        compare("compare different sizes", ["good.exr", "small.exr"], 3, "small.exr"),
        compare("compare missing reference", ["good.exr", "nosuch.exr"], 3, "nosuch.exr"),
        compare("compare truncated test image", ["truncated.exr", "good.exr"], 3, "truncated.exr"),
        compare("compare truncated PNG named .exr", ["png_truncated.exr", "good.exr"], 3, "png_truncated.exr", 9),
        compare("compare missing channel", ["good.exr", "good2.exr", "--channels", "nosuch.X"], 3, "good.exr"),
        compare("compare --crop overflow with a heatmap", ["good.exr", "good2.exr", "--crop", "2147483600,0,100,10",
                                                           "--heatmap", "hm.png"], 3, defect=3),
        # A crop outside the images is a problem of these inputs (exit 3), a crop with no area of the option (2).
        compare("compare --crop overflow", ["good.exr", "good2.exr", "--crop", "2147483600,0,100,10"], 3, defect=3),
        compare("compare --crop outside the image", ["good.exr", "good2.exr", "--crop", "4,4,8,8"], 3, defect=8),
        compare("compare --metric bogus", ["good.exr", "good2.exr", "--metric", "bogus"], 2, "bogus", 9),
        compare("compare --ppd 0", ["good.exr", "good2.exr", "--metric", "flip", "--ppd", "0"], 2, defect=12),
        compare("compare --fail-above without a value", ["good.exr", "good2.exr", "--fail-above", "rmse"], 2, "rmse", 9),
        compare("compare --mask of another size", ["good.exr", "good2.exr", "--mask", "mask_small.exr"], 3,
                "mask_small.exr"),
        compare("compare --csv is an input", ["good.exr", "good2.exr", "--csv", "good2.exr"], 3, "good2.exr"),
        compare("compare --heatmap beside an input", ["good.exr", "good2.exr", "--heatmap", "good2.png"], 3,
                "good2.exr"),
        compare("compare --frames 3-1", ["seq.####.exr", "seq.####.exr", "--frames", "3-1"], 2),
        compare("compare --frames 1-2000000000", ["seq.####.exr", "seq.####.exr", "--frames", "3-2000000000"], 3,
                "seq.0003.exr", 5),
        compare("compare a folder with a file", ["folder.exr", "good.exr"], 2, "folder.exr"),
        info("info zero-byte EXR", "empty.exr"),
        info("info garbage EXR", "garbage.exr"),
        info("info truncated EXR", "truncated.exr"),
        info("info header declares 8000x8000", "declared_8000.exr", defect=7),
        info("info header declares 100000x100000", "huge_100000.exr", defect=7),
        info("info 60 KB of an 8000x8000 file", "truncated_8000.exr", defect=7),
        info("info header alone declares 100000x100000", "declared_100000.exr", defect=7),
        case("compare header alone declares 100000x100000", ["compare", "declared_100000.exr", "good.exr"], 3,
             "declared_100000.exr", 7),
        info("info truncated PNG named .exr", "png_truncated.exr", defect=9),
        info("info missing file", "nosuch.exr"),
        info("info directory", "folder.exr"),
        preview("preview missing channel", ["good.exr", "-o", "out.png", "--channels", "nosuch.X"], 3,
                "good.exr", 9),
        preview("preview garbage EXR", ["garbage.exr", "-o", "out.png"], 3, "garbage.exr"),
        # A preview must be named .png: this command line is refused before any file is looked at.
        preview("preview output is the input", ["good.exr", "-o", "good.exr"], 2, "good.exr"),
        preview("preview two channels", ["good.exr", "-o", "out.png", "--channels", "R,G"], 2, defect=8),
        preview("preview missing OCIO config", ["good.exr", "-o", "out.png", "--ocio-config", "nosuch.ocio"], 3,
                "nosuch.ocio"),
        preview("preview unknown display", ["good.exr", "-o", "out.png", "--display", "nosuch"], 2, "nosuch"),
        preview("preview into a folder", ["good.exr", "-o", "folder.png"], 3, "folder.png", 9),
        case("unknown command", ["frobnicate"], 2, "frobnicate", 9),
    ] + analyze_cases()


def analyze_cases():
    """`aaf analyze wedge`: wedges and options that mean nothing are usage errors."""
    def wedge(name, args, names=None):
        return case(name, ["analyze", "wedge", *args], 2, names)

    return [
        wedge("analyze wedge --smin above --smax", ["--smin", "2", "--smax", "1"], "--smin"),
        wedge("analyze wedge --smin equal to --smax", ["--smin", "1", "--smax", "1"], "--smin"),
        wedge("analyze wedge --smin -1", ["--smin", "-1", "--smax", "1"], "--smin"),
        wedge("analyze wedge --smax inf", ["--smin", "1", "--smax", "inf"], "--smax"),
        wedge("analyze wedge --filters 0", ["--smin", "1", "--smax", "2", "--filters", "0"], "--filters"),
        wedge("analyze wedge --random with --smin", ["--random", "5", "--smin", "1", "--smax", "2"], "--random"),
        wedge("analyze wedge --box with --gauss", ["--smin", "1", "--smax", "2", "--box", "--gauss"], "--box"),
        wedge("analyze wedge without slopes", [], "--smin"),
        case("analyze unknown subcommand", ["analyze", "wedgee"], 2, "wedgee"),
    ]


def fuzz_cases():
    """What the libFuzzer harnesses found (tests/README.md), as command lines."""
    for name in os.listdir(FINDINGS):
        shutil.copyfile(os.path.join(FINDINGS, name), path(name))
    string_attribute = "read_aovs-string_attribute_1_7GB.exr"  # OpenEXR fills the declared 1.7 GB string
    webp_header = "read_aovs-webp_header_declaring_2_5GB.exr"  # 26 bytes: OIIO's WebP reader allocated 3.2 GB
    no_channels = "read_aovs-header_without_channels_2_1GB.exr"  # 830 bytes: OpenEXR allocated 2.1 GB
    # 1.4 KB, a valid 131332x4 header whose pixels fail to inflate: OpenImageIO's read_scanlines reserves
    # 2.5 GB that it never touches (peak RSS stays near 170 MB); kept so the reservation stays harmless.
    scanline_reserve = "read_aovs-oiio_reserves_2_5GB_for_scanlines.exr"
    return [
        case("fuzz: info on an EXR whose pixels fail to inflate after a large reservation", ["info", scanline_reserve],
             3, scanline_reserve, 7),
        case("fuzz: info on an EXR header whose channel list is unnamed", ["info", no_channels], 3, no_channels, 7),
        case("fuzz: info on a 26-byte WebP header declaring 14898x10798", ["info", webp_header], 3, webp_header, 7),
        case("fuzz: info EXR whose string attribute declares 1.7 GB", ["info", string_attribute], 3,
             string_attribute, 7),
        case("fuzz: filter EXR whose string attribute declares 1.7 GB",
             ["filter", "gaussian", string_attribute, "-o", "out.exr"], 3, string_attribute, 7),
        case("fuzz: compare --frames with a 14-digit frame", ["compare", "seq.####.exr", "seq.####.exr",
                                                              "--frames", "1,10090009010009"], 2, defect=9),
        # The two frames on disk are filtered (their outputs are good work), the third is missing.
        case("fuzz: filter --frames 1-11098100 over two frames",
             ["filter", "gaussian", "seq.####.exr", "-o", "out.####.exr", "--frames", "1-11098100",
              "--progress", "none"], 3, "seq.0003.exr", 5, creates=["out.0001.exr", "out.0002.exr"]),
    ]


def python_module_cases():
    """The Python module `aaf` (libaaf/python), each call in a small driver
    (tests/bad_inputs/python_case.py: Y is an 8x8 plane, RGB an aaf.Aovs):
    a bad argument is aaf.Error naming it (exit 2), a bad file
    aaf.InputError naming the file (exit 3), and nothing is written."""
    def py(name, code, exit_code, names, **extra):
        return case("python: " + name, [code], exit_code, names, program="python", **extra)

    write = "aaf.write('out.exr', %s)"
    return [
        py("an int attribute of 2**40", write % "aaf.Aovs({'Y': Y}, {'frame_id': 2 ** 40})", 2, "frame_id"),
        py("an int attribute below -2**31", write % "aaf.Aovs({'Y': Y}, {'n': -2 ** 31 - 1})", 2, "'n'"),
        py("a float attribute of 1e300", write % "aaf.Aovs({'Y': Y}, {'far': 1e300})", 2, "far"),
        py("a vector attribute with a str", write % "aaf.Aovs({'Y': Y}, {'v': (1, 'a', 2)})", 2, "'v'"),
        py("a channel name that is an int", write % "aaf.Aovs({1: Y})", 2, "channel name"),
        py("an attribute name that is a tuple", write % "aaf.Aovs({'Y': Y}, {(1, 2): 3})", 2, "attribute name"),
        py("an empty channel name", write % "aaf.Aovs({'': Y, 'G': Y})", 2, "channel ''"),
        py("write to .png", "aaf.write('out.png', RGB)", 2, "out.png"),
        py("write to .JPEG", "aaf.write('out.JPEG', RGB)", 2, "out.JPEG"),
        py("a 4 TB conversion fails as out of memory",
           write % "aaf.Aovs({'Y': np.broadcast_to(np.float64(1), (1000000, 1000000))})", 2, "out of memory"),
        py("a 3-D channel", write % "aaf.Aovs({'Y': np.zeros((8, 8, 3))})", 2, "'Y'"),
        py("a channel with no pixels", write % "aaf.Aovs({'Y': np.zeros((0, 8))})", 2, "'Y'"),
        py("a complex channel", write % "aaf.Aovs({'Y': np.zeros((8, 8), complex)})", 2, "'Y'"),
        py("a channel of strings", write % "aaf.Aovs({'Y': [['a', 'b']]})", 2, "'Y'"),
        py("channels of two shapes", write % "aaf.Aovs({'R': Y, 'G': np.zeros((4, 4))})", 2, "'G'"),
        py("aovs that are not aaf.Aovs", write % "{'Y': Y}", 2, "aovs"),
        py("channels that are not a dict", "aaf.Aovs(5)", 2, "channels"),
        py("write compression unknown", "aaf.write('out.exr', RGB, compression='bogus')", 3, "bogus"),
        py("write into a missing folder", "aaf.write('nosuch/out.exr', RGB)", 3, "nosuch/out.exr"),
        py("write onto a folder", "aaf.write('folder.exr', RGB)", 3, "folder.exr"),
        py("compare peak 0", "aaf.compare(RGB, RGB, peak=0)", 2, "peak"),
        py("compare peak NaN", "aaf.compare(RGB, RGB, peak=float('nan'))", 2, "peak"),
        py("compare peak inf", "aaf.compare(RGB, RGB, peak=float('inf'))", 2, "peak"),
        py("compare unknown metric", "aaf.compare('good.exr', 'good2.exr', metrics=['bogus'])", 2, "bogus"),
        py("compare a metric that is an int", "aaf.compare(RGB, RGB, metrics=[3])", 2, "metrics"),
        py("compare a path with arrays", "aaf.compare('good.exr', RGB)", 2, "test"),
        py("compare a missing reference", "aaf.compare('good.exr', 'nosuch.exr')", 3, "nosuch.exr"),
        py("compare different sizes", "aaf.compare('good.exr', 'small.exr')", 3, "small.exr"),
        py("read a path that is an int", "aaf.read(5)", 2, "path"),
        py("read a missing file", "aaf.read('nosuch.exr')", 3, "nosuch.exr"),
        py("read garbage", "aaf.read('garbage.exr')", 3, "garbage.exr"),
        py("read a truncated EXR", "aaf.read('truncated.exr')", 3, "truncated.exr"),
        py("read a header declaring 100000x100000", "aaf.read('declared_100000.exr')", 3, "declared_100000.exr"),
        py("filter threads 2**40", "aaf.filter('gaussian', aaf.read('good.exr'), threads=2 ** 40)", 2, "threads"),
        py("filter a parameter of None", "aaf.filter('gaussian', aaf.read('good.exr'), sigma=None)", 2, "sigma"),
        py("filter a method name that is an int", "aaf.filter(3, RGB)", 2, "method"),
        py("filter a map role that is an int", "aaf.filter('aaf', aaf.read('good.exr'), map={1: 'x'})", 2, "map"),
        py("filter missing visibility", "aaf.filter('aaf', aaf.read('missing_visibility.exr'))", 3, "visibility"),
        py("write a good file", "aaf.write('out.exr', aaf.read('good.exr'))", 0, None, creates=["out.exr"]),
    ]


def aaf_complete_cases():
    """scripts/blender/aaf_complete.py (run directly, as the README says):
    an output that is an input under any name is refused, a failure writes
    nothing (the output goes through a temporary beside it)."""
    cycles = {"ViewLayer.Combined." + c: aov_planes(1)["R"] for c in "RGB"}
    cycles["ViewLayer.Depth.Z"] = np.full((SIZE, SIZE), 3.0, np.float32)
    write_exr("cycles.exr", cycles, attributes={})

    def complete(name, args, exit_code, names, **extra):
        return case("aaf_complete: " + name, args, exit_code, names, program="aaf_complete", **extra)

    return [
        complete("output is the Cycles input", ["cycles.exr", "good.exr", "cycles.exr"], 3, "cycles.exr"),
        complete("output is the aaf input", ["cycles.exr", "good.exr", "good.exr"], 3, "good.exr"),
        complete("output is the input spelt ./", ["cycles.exr", "good.exr", "./cycles.exr"], 3, "./cycles.exr"),
        complete("output is a symlink to the input", ["cycles.exr", "good.exr", "link.exr"], 3, "link.exr",
                 setup={"symlink": {"link.exr": "cycles.exr"}}),
        complete("output is a hard link to the input", ["cycles.exr", "good.exr", "hard.exr"], 3, "hard.exr",
                 setup={"hardlink": {"hard.exr": "good.exr"}}),
        complete("two arguments", ["cycles.exr", "good.exr"], 2, "usage"),
        complete("output named .png", ["cycles.exr", "good.exr", "out.png"], 2, "out.png"),
        complete("missing Cycles file", ["nosuch.exr", "good.exr", "out.exr"], 3, "nosuch.exr"),
        complete("garbage Cycles file", ["garbage.exr", "good.exr", "out.exr"], 3, "garbage.exr"),
        complete("no Combined pass", ["good.exr", "good.exr", "out.exr"], 3, "good.exr"),
        complete("aaf AOVs of another size", ["cycles.exr", "small.exr", "out.exr"], 3, "small.exr"),
        complete("output in a missing folder", ["cycles.exr", "good.exr", "nosuch/out.exr"], 3, "nosuch/out.exr"),
        complete("output is a folder", ["cycles.exr", "good.exr", "folder.exr"], 3, "folder.exr"),
        complete("completes a Cycles file", ["cycles.exr", "good.exr", "out.exr"], 0, None, creates=["out.exr"]),
    ]


def slurm_filter_cases():
    """scripts/farm/slurm_filter.sh (AAF is the aaf under test): the CLI's
    exit codes and one error line; the last frame on disk is found whatever
    the folder is named, counting only the pattern's own frames."""
    task = {"SLURM_ARRAY_TASK_ID": "1", "SLURM_ARRAY_TASK_STEP": "4"}

    def slurm(name, args, exit_code, names, env=task, **extra):
        return case("slurm_filter: " + name, args, exit_code, names, program="slurm_filter", env=env, **extra)

    odd = "shot [1] *'s"
    return [
        slurm("no arguments", [], 2, "usage"),
        slurm("one argument", ["seq.####.exr"], 2, "usage"),
        slurm("LAST_FRAME=abc", ["seq.####.exr", "out.####.exr"], 2, "LAST_FRAME='abc'",
              env={**task, "LAST_FRAME": "abc"}),
        slurm("not an array task", ["seq.####.exr", "out.####.exr"], 2, "SLURM_ARRAY_TASK_ID", env={}),
        slurm("array step 0", ["seq.####.exr", "out.####.exr"], 2, "SLURM_ARRAY_TASK_STEP",
              env={**task, "SLURM_ARRAY_TASK_STEP": "0"}),
        slurm("a pattern without a frame field", ["good.exr", "out.####.exr"], 2, "good.exr"),
        slurm("no frame on disk", ["nosuch.####.exr", "out.####.exr"], 3, "nosuch.####.exr"),
        slurm("a pattern in a missing folder", ["nosuch/seq.####.exr", "out.####.exr"], 3, "nosuch/seq.####.exr"),
        slurm("only a stray file beside the pattern", ["noisy.####.exr", "out.####.exr"], 3, "noisy.####.exr",
              setup={"copy": {"good.exr": "noisy.v2.exr"}}),
        slurm("a folder with a space, brackets and a star, beside stray files",
              [odd + "/seq.####.exr", odd + "/out.####.exr"], 0, None,
              setup={"copy": {"seq.0001.exr": odd + "/seq.0001.exr", "seq.0002.exr": odd + "/seq.0002.exr",
                              "good.exr": odd + "/seq.v2.exr", "good2.exr": odd + "/seq.00009.exr"}},
              creates=[odd + "/out.0001.exr", odd + "/out.0002.exr"]),
        slurm("a chunk past the last frame", ["seq.####.exr", "out.####.exr"], 0, None,
              env={**task, "SLURM_ARRAY_TASK_ID": "5"}),
    ]


def blender_bridge_cases():
    """scripts/blender/aaf_bridge.py in Blender's factory scene (a cube, a
    point light, a camera): aaf's exit codes, one error line, and a failed
    export leaves no file. Few: each starts Blender (about 2 s)."""
    def bridge(name, args, exit_code, names):
        return case("blender bridge: " + name, args, exit_code, names, program="blender_bridge")

    return [
        bridge("export a scene without an area light", ["export", "shot.json"], 3, "shot.json"),
        bridge("export into a missing folder", ["export", "nosuch/shot.json"], 3, "nosuch/shot.json"),
        bridge("load a missing file", ["load", "nosuch.exr"], 3, "nosuch.exr"),
        bridge("load a text file", ["load", "text.exr"], 3, "text.exr"),
        bridge("unknown command", ["frobnicate"], 2, "frobnicate"),
    ]


def ratio_planes(seed, size=SIZE, motion=True):
    """The ratio estimator's inputs (U, S_N <= U_N, their luminance, P, N, pixel.size) and, with
    `motion`, a half-pixel camera pan: one frame of a `ratio --temporal` sequence."""
    rng = np.random.default_rng(seed)
    y, x = np.mgrid[0:size, 0:size].astype(np.float32)
    unshadowed = np.full((size, size), 0.5, np.float32) + 0.1 * rng.random((size, size), np.float32)
    shadowed = unshadowed * np.clip(x / (size - 1) + 0.2 * rng.standard_normal((size, size)), 0, 1)
    planes = {"P.X": x * 0.1, "P.Y": np.zeros_like(x), "P.Z": y * 0.1,
              "N.X": np.zeros_like(x), "N.Y": np.ones_like(x), "N.Z": np.zeros_like(x),
              "pixel.size": np.full_like(x, 0.1)}
    for c in "RGB":
        planes["ratio.U." + c] = np.full_like(x, 0.6)
        planes["ratio.S." + c] = shadowed.astype(np.float32)
        planes["ratio.Un." + c] = unshadowed
        planes[c] = shadowed.astype(np.float32)
    planes["ratio.S.Y"], planes["ratio.Un.Y"] = shadowed.astype(np.float32), unshadowed
    if motion:
        planes["motion.X"], planes["motion.Y"] = np.full_like(x, 0.5), np.zeros_like(x)
    return planes


def write_temporal_files():
    """Sequences for `ratio --temporal`: good frames, frames without motion, a gap, a bad history
    frame, a history frame of another size."""
    for frame in (1, 2, 3):
        write_exr("rt.%04d.exr" % frame, ratio_planes(10 + frame), RATIO_BEAUTY)
    for frame in (1, 2):
        write_exr("rtnm.%04d.exr" % frame, ratio_planes(20 + frame, motion=False), RATIO_BEAUTY)
    for frame in (1, 3):
        write_exr("rtgap.%04d.exr" % frame, ratio_planes(30 + frame), RATIO_BEAUTY)
    write_bytes("rtbad.0001.exr", open(path("rt.0001.exr"), "rb").read()[:300])
    write_exr("rtbad.0002.exr", ratio_planes(42), RATIO_BEAUTY)
    write_exr("rtsize.0001.exr", ratio_planes(51, size=4), RATIO_BEAUTY, size=4)
    write_exr("rtsize.0002.exr", ratio_planes(52), RATIO_BEAUTY)


def temporal_sequence_cases():
    """`aaf filter ratio --temporal` over sequences: patterns, --frames, --skip-existing with stale
    or partial outputs, histories that cannot be made."""
    def temporal(name, pattern, code, names=None, extra_args=(), output="o.####.exr", **extra):
        return case(name, ["filter", "ratio", "--temporal", pattern, "-o", output, "--progress", "none",
                           *extra_args], code, names, **extra)

    outputs = ["o.%04d.exr" % f for f in (1, 2, 3)]
    return [
        temporal("temporal sequence writes every frame", "rt.####.exr", 0, creates=outputs),
        temporal("temporal chunk writes its frames only, its history in memory", "rt.####.exr", 0,
                 extra_args=("--frames", "2-3"), creates=outputs[1:]),
        temporal("temporal every other frame", "rt.####.exr", 0, extra_args=("--frames", "1-3x2"),
                 creates=[outputs[0], outputs[2]]),
        temporal("temporal --skip-existing redoes a stale output", "rt.####.exr", 0,
                 extra_args=("--frames", "3-3", "--skip-existing"),
                 setup={"copy": {"stale_output.exr": "o.0003.exr"}}, creates=outputs[2:]),
        temporal("temporal --skip-existing redoes a killed run's partial frame and an output made elsewhere",
                 "rt.####.exr", 0, extra_args=("--skip-existing",),
                 setup={"copy": {"truncated.exr": "o.0001.exr", "good.exr": "o.0002.exr"}}, creates=outputs),
        temporal("temporal --skip-existing with a temporary a killed run left", "rt.####.exr", 0,
                 extra_args=("--frames", "2-2", "--skip-existing"),
                 setup={"copy": {"stale_output.exr": ".o.0002.exr.tmp-999999-0"}}, creates=outputs[1:2],
                 removes=[".o.0002.exr.tmp-999999-0"]),
        temporal("temporal a gap in the sequence starts a new history", "rtgap.####.exr", 0,
                 creates=[outputs[0], outputs[2]]),
        temporal("temporal on a single file", "rt.0002.exr", 0, output="o.exr", creates=["o.exr"]),
        temporal("temporal missing motion", "rtnm.####.exr", 3, "rtnm.0001.exr"),
        temporal("temporal missing motion in a chunk", "rtnm.####.exr", 3, "rtnm.0001.exr",
                 extra_args=("--frames", "2-2")),
        temporal("temporal history frame is garbage", "rtbad.####.exr", 3, "rtbad.0001.exr",
                 extra_args=("--frames", "2-2")),
        temporal("temporal history frame of another size", "rtsize.####.exr", 3, "rtsize.0002.exr",
                 extra_args=("--frames", "2-2")),
        temporal("temporal frame missing from the sequence", "rt.####.exr", 3, "rt.0005.exr",
                 extra_args=("--frames", "5-5")),
        temporal("temporal missing pattern folder", "nosuch/rt.####.exr", 3, "nosuch"),
        temporal("temporal pattern with no frames on disk", "none.####.exr", 3, "none.####.exr"),
        temporal("temporal --frames 3-1", "rt.####.exr", 2, "3-1", extra_args=("--frames", "3-1")),
        temporal("temporal --frames empty", "rt.####.exr", 2, "--frames", extra_args=("--frames", "")),
        temporal("temporal --frames step 0", "rt.####.exr", 2, "--frames", extra_args=("--frames", "1-3x0")),
        temporal("temporal --frames on a single file", "rt.0001.exr", 2, "--frames", output="o.exr",
                 extra_args=("--frames", "1-2")),
        temporal("temporal input pattern, output file", "rt.####.exr", 2, "o.exr", output="o.exr"),
        temporal("temporal output pattern, input file", "rt.0001.exr", 2, "o.####.exr"),
        temporal("temporal output pattern is the input", "rt.####.exr", 3, "rt.0001.exr", output="rt.####.exr"),
        temporal("temporal output pattern is the input spelt %04d", "rt.####.exr", 3, "rt.0001.exr",
                 output="rt.%04d.exr"),
        temporal("temporal --temporal-alpha 0", "rt.####.exr", 2, "temporal_alpha",
                 extra_args=("--temporal-alpha", "0")),
        temporal("temporal --temporal-alpha 1.5", "rt.####.exr", 2, "temporal_alpha",
                 extra_args=("--temporal-alpha", "1.5")),
        temporal("temporal --temporal-alpha nan", "rt.####.exr", 2, "temporal_alpha",
                 extra_args=("--temporal-alpha", "nan")),
        temporal("temporal --grey with --estimator stochastic, before reading", "nosuch.####.exr", 2, "--grey",
                 extra_args=("--grey", "--estimator", "stochastic")),
    ]


def render_filter_param_cases():
    """`aaf render --filter` with bad --filter-param values: refused with exit 2 before rendering."""
    sequence = ["render", "scene.json", "-o", "o.####.exr", "--frames", "1-2", "--width", "8", "--height", "8",
                "--spp", "1", "--progress", "none"]

    def bad(name, params, names=None, extra_args=()):
        args = sequence + list(extra_args)
        for p in params:
            args += ["--filter-param", p]
        return case(name, args, 2, names)

    def ratio(name, params, names=None, extra_args=()):
        return bad(name, params, names, ("--filter", "ratio", *extra_args))

    return [
        ratio("render --filter ratio temporal without motion in --aovs", ["temporal=true"], "--aovs ratio,motion",
              ("--aovs", "ratio")),
        ratio("render --filter ratio denoiser=aaf without the shadow AOVs", ["denoiser=aaf"], "denoiser=aaf",
              ("--aovs", "ratio,motion")),
        ratio("render --filter ratio grey with the stochastic estimator", ["grey=true", "estimator=stochastic"],
              "--grey"),
        ratio("render --filter ratio temporal=maybe", ["temporal=maybe"], "temporal=maybe"),
        ratio("render --filter ratio temporal_alpha=0", ["temporal=true", "temporal_alpha=0"], "temporal_alpha=0"),
        ratio("render --filter ratio temporal-alpha=2", ["temporal-alpha=2"], "temporal-alpha=2"),
        ratio("render --filter ratio temporal_alpha=nan", ["temporal_alpha=nan"], "temporal_alpha=nan"),
        ratio("render --filter ratio estimator=bogus", ["estimator=bogus"], "estimator=bogus"),
        ratio("render --filter ratio noise_radius=0", ["noise_radius=0"], "noise_radius=0"),
        ratio("render --filter ratio temporal without a value", ["temporal"], "temporal"),
        ratio("render --filter ratio =true", ["=true"], "=true"),
        bad("render --filter gaussian temporal=true", ["temporal=true"], "temporal=true", ("--filter", "gaussian")),
        bad("render --filter aaf mu_from_spp with fixed_mu", ["mu_from_spp=true", "fixed_mu=true"], "fixed mu",
            ("--filter", "aaf")),
        case("render --filter ratio temporal sequence into one file",
             ["render", "scene.json", "-o", "o.exr", "--frames", "1-2", "--width", "8", "--height", "8", "--spp",
              "1", "--filter", "ratio", "--filter-param", "temporal=true"], 2, "--frames"),
        case("render --filter ratio temporal sequence, frame 2 alone with a stale output",
             sequence[:5] + ["2-2"] + sequence[6:] + ["--filter", "ratio", "--filter-param", "temporal=true",
                                                      "--skip-existing"], 0,
             setup={"copy": {"stale_output.exr": "o.0002.exr"}}, creates=["o.0002.exr"]),
    ]



# Real 8x8 renders of each tracer group, the bases of the method cases below:
# committed (testdata/bad/templates/), so the corpus needs no built aaf;
# `make_bad_corpus.py --templates AAF` renders them again with that aaf.
TEMPLATES = os.path.join(BAD, "templates")
TEMPLATE_GROUPS = {"maaf": "maaf", "maaf6": "maaf6", "ratio": "ratio", "ratio_aaf": "ratio,shadow,all",
                   "isg": "isg,all"}


def render_templates(aaf):
    import subprocess
    os.makedirs(TEMPLATES, exist_ok=True)
    for name, groups in TEMPLATE_GROUPS.items():
        subprocess.run([aaf, "render", "grids", "-o", os.path.join(TEMPLATES, name + ".exr"), "--width", "8",
                        "--height", "8", "--spp", "4", "--progress", "none", "--aovs", groups], check=True)


def read_template(name):
    image = oiio.ImageInput.open(os.path.join(TEMPLATES, name + ".exr"))
    if image is None:
        sys.exit("missing template %s (make_bad_corpus.py --templates AAF): %s" % (name, oiio.geterror()))
    spec = oiio.ImageSpec(image.spec())
    pixels = image.read_image(oiio.FLOAT)
    image.close()
    return spec, pixels


def write_variant(name, template, attributes=None, fill=None, drop=(), rename=None):
    """`template` with header `attributes` set ((type, value); type None for
    OIIO's own from the value), channels matching `fill` (prefix -> value)
    overwritten, those in `drop` removed and those in `rename` (prefix ->
    prefix) renamed."""
    spec, pixels = read_template(template)
    names = list(spec.channelnames)
    keep = [i for i, n in enumerate(names) if n not in drop]
    for prefix, value in (fill or {}).items():
        for i, n in enumerate(names):
            if n.startswith(prefix):
                pixels[:, :, i] = value
    out_names = []
    for i in keep:
        n = names[i]
        for old, new in (rename or {}).items():
            if n.startswith(old):
                n = new + n[len(old):]
        out_names.append(n)
    out_spec = oiio.ImageSpec(spec.width, spec.height, len(keep), oiio.FLOAT)
    out_spec.channelnames = tuple(out_names)
    out_spec.attribute("compression", "zip")
    out_spec.attribute("DateTime", FIXED_DATE)
    for attribute in spec.extra_attribs:
        if attribute.name.startswith("aaf:"):
            out_spec.attribute(attribute.name, attribute.type, attribute.value)
    for key, (kind, value) in (attributes or {}).items():
        if kind is None:
            out_spec.attribute(key, value)
        else:
            out_spec.attribute(key, oiio.TypeDesc(kind), value)
    out = oiio.ImageOutput.create(path(name))
    if not out.open(path(name), out_spec) or not out.write_image(np.ascontiguousarray(pixels[:, :, keep])):
        sys.exit("cannot write %s: %s" % (name, oiio.geterror()))
    out.close()


NAN = float("nan")


def write_method_inputs():
    for template in TEMPLATE_GROUPS:
        write_variant(template + ".exr", template)
    for name, value in [("1e6", 1000000), ("max", 2147483647), ("neg", -1)]:
        write_variant("ratio_lights_%s.exr" % name, "ratio", {"aaf:ratio:lights": ("int", value)})
    write_variant("ratio_lights_string.exr", "ratio", {"aaf:ratio:lights": (None, "three")})
    write_variant("ratio_huge.exr", "ratio_aaf", fill={"ratio.": 3e38})
    write_variant("ratio_myU.exr", "ratio", rename={"ratio.U.": "myU.", "ratio.L0.U.": "myU.L0."},
                  attributes={"aaf:ratio:lights": ("int", 0)})
    for name, value in [("zero", 0.0), ("neg", -3.0), ("nan", NAN), ("1e30", 1e30)]:
        write_variant("isg_focal_%s.exr" % name, "isg", {"aaf:camera:focal_px": ("float", value)})
    write_variant("isg_focal_string.exr", "isg", {"aaf:camera:focal_px": (None, "wide")})
    write_variant("isg_eye_nan.exr", "isg", {"aaf:camera:eye": ("float[3]", (NAN, 1.0, 1.0))})
    for name, value in [("nan", NAN), ("neg", -0.1)]:
        write_variant("isg_aperture_%s.exr" % name, "isg", {"aaf:camera:aperture_radius_m": ("float", value)})
    write_variant("isg_focus_zero.exr", "isg", {"aaf:camera:aperture_radius_m": ("float", 0.05),
                                                "aaf:camera:focus_distance_m": ("float", 0.0)})
    write_variant("isg_light_sigma_nan.exr", "isg", {"aaf:light:sigma_m": ("float", NAN)})
    write_variant("isg_no_depth.exr", "isg", drop=("Z",))
    write_variant("isg_huge.exr", "isg", fill={"glossy.": 3e38, "reflect.": 3e38, "pinhole.": 3e38})
    write_variant("maaf_pairs_1e6.exr", "maaf", {"aaf:maaf:pairs": ("int", 1000000)})
    write_variant("maaf_pairs_neg.exr", "maaf", {"aaf:maaf:pairs": ("int", -3)})
    write_variant("maaf_omega_nan.exr", "maaf", {"aaf:maaf:omega_y_max": ("float", NAN)})
    write_variant("maaf_light_normal_zero.exr", "maaf", {"aaf:light:normal": ("float[3]", (0.0, 0.0, 0.0))})
    write_variant("maaf_huge.exr", "maaf", fill={"maaf.": 3e38, "unshadowed.": 3e38})
    write_variant("maaf6_pairs_huge.exr", "maaf6", {"aaf:maaf6:pairs": ("int", 2147483647)})
    write_variant("maaf6_omega_direct_nan.exr", "maaf6", {"aaf:maaf6:omega_y_direct": ("float", NAN)})
    write_variant("maaf6_omega_indirect_zero.exr", "maaf6", {"aaf:maaf6:omega_y_indirect": ("float", 0.0)})
    write_variant("maaf6_omega_u_neg.exr", "maaf6", {"aaf:maaf6:omega_u": ("float", -1.0)})
    write_variant("maaf6_huge.exr", "maaf6", fill={"maaf6.": 3e38})
    good = aov_planes(1)
    write_exr("no_rgb.exr", {n: v for n, v in good.items() if n not in ("R", "G", "B")})
    write_exr("huge_beauty.exr", {n: (np.full_like(v, 3e38) if n in ("R", "G", "B", "shadow.V") else v)
                                  for n, v in good.items()})
    write_exr("unshadowed_huge.exr", {n: (np.full_like(v, 3e38) if n.startswith("unshadowed.") else v)
                                      for n, v in good.items()})


def method_input_cases():
    def filter_(name, method, input_file, code=3, names=None, extra_args=(), **extra):
        return case(name, ["filter", method, input_file, "-o", "out.exr", *extra_args], code,
                    names if names is not None else input_file, **extra)

    def usage(name, args, names=None, **extra):
        return case(name, args, 2, names, **extra)

    render8 = ["--width", "8", "--height", "8", "--spp", "1", "--progress", "none"]
    warn = lambda name, options, text: case(name, ["render", "grids", "-o", "w.exr", *render8, *options], 0,
                                            creates=["w.exr"], warns=text)
    return [
        # Declared counts against the channels present (before anything is sized by them).
        filter_("ratio aaf:ratio:lights 1e6", "ratio", "ratio_lights_1e6.exr"),
        filter_("ratio aaf:ratio:lights 2^31-1", "ratio", "ratio_lights_max.exr"),
        filter_("ratio aaf:ratio:lights -1", "ratio", "ratio_lights_neg.exr"),
        filter_("ratio aaf:ratio:lights a string", "ratio", "ratio_lights_string.exr"),
        filter_("maaf aaf:maaf:pairs 1e6", "maaf", "maaf_pairs_1e6.exr"),
        filter_("maaf aaf:maaf:pairs -3", "maaf", "maaf_pairs_neg.exr"),
        filter_("maaf6 aaf:maaf6:pairs 2^31-1", "maaf6", "maaf6_pairs_huge.exr"),
        # Header attributes out of range: exit 3 naming the attribute (and the file).
        filter_("isg-shadow focal_px 0", "isg-shadow", "isg_focal_zero.exr", names="aaf:camera:focal_px"),
        filter_("isg-shadow focal_px negative", "isg-shadow", "isg_focal_neg.exr", names="aaf:camera:focal_px"),
        filter_("isg-glossy focal_px NaN", "isg-glossy", "isg_focal_nan.exr", names="aaf:camera:focal_px"),
        filter_("isg-dof focal_px 1e30", "isg-dof", "isg_focal_1e30.exr", names="aaf:camera:focal_px"),
        filter_("isg-shadow focal_px a string", "isg-shadow", "isg_focal_string.exr",
                names="aaf:camera:focal_px"),
        filter_("isg-glossy eye NaN", "isg-glossy", "isg_eye_nan.exr", names="aaf:camera:eye"),
        filter_("isg-dof aperture NaN", "isg-dof", "isg_aperture_nan.exr", names="aaf:camera:aperture_radius_m"),
        filter_("isg-dof aperture negative", "isg-dof", "isg_aperture_neg.exr",
                names="aaf:camera:aperture_radius_m"),
        filter_("isg-dof focus distance 0 with a lens", "isg-dof", "isg_focus_zero.exr",
                names="aaf:camera:focus_distance_m"),
        filter_("isg-shadow light sigma NaN", "isg-shadow", "isg_light_sigma_nan.exr", names="aaf:light:sigma_m"),
        filter_("maaf omega_y_max NaN", "maaf", "maaf_omega_nan.exr", names="aaf:maaf:omega_y_max"),
        filter_("maaf light normal zero", "maaf", "maaf_light_normal_zero.exr", names="aaf:light:normal"),
        filter_("maaf6 omega_y_direct NaN", "maaf6", "maaf6_omega_direct_nan.exr",
                names="aaf:maaf6:omega_y_direct"),
        filter_("maaf6 omega_y_indirect 0", "maaf6", "maaf6_omega_indirect_zero.exr",
                names="aaf:maaf6:omega_y_indirect"),
        filter_("maaf6 omega_u negative", "maaf6", "maaf6_omega_u_neg.exr", names="aaf:maaf6:omega_u"),
        # A role is read only from its own name: no depth from P.Z, no beauty from unshadowed.R/G/B.
        filter_("isg-shadow without Z (P.Z present)", "isg-shadow", "isg_no_depth.exr", names="depth"),
        filter_("isg-dof without Z (P.Z present)", "isg-dof", "isg_no_depth.exr", names="depth"),
        # Without R,G,B the composed beauty is written to R,G,B, unshadowed.R/G/B left as they were.
        filter_("gaussian without R,G,B (unshadowed present)", "gaussian", "no_rgb.exr", code=0, names="",
                creates=["out.exr"]),
        filter_("aaf without R,G,B (unshadowed present)", "aaf", "no_rgb.exr", code=0, names="",
                creates=["out.exr"]),
        filter_("isg-glossy on a ratio render", "isg-glossy", "ratio.exr"),
        filter_("maaf6 on a maaf render", "maaf6", "maaf.exr"),
        # Finite input, finite output (or an error naming the channel).
        filter_("ratio inputs 3e38 (aaf widths, control variate)", "ratio", "ratio_huge.exr", code=0, names="",
                extra_args=("--denoiser", "aaf", "--estimator", "control-variate"), creates=["out.exr"]),
        case("gaussian beauty 3e38", ["filter", "gaussian", "huge_beauty.exr", "-o", "out.exr"], 0,
             creates=["out.exr"]),
        case("aaf unshadowed 3e38", ["filter", "aaf", "unshadowed_huge.exr", "-o", "out.exr"], 0,
             creates=["out.exr"]),
        case("maaf sums 3e38", ["filter", "maaf", "maaf_huge.exr", "-o", "out.exr"], 0, creates=["out.exr"]),
        # Its beauty is not the sum of its 3e38 layers, so the corrected beauty leaves float's range: refused.
        case("maaf6 layers 3e38", ["filter", "maaf6", "maaf6_huge.exr", "-o", "out.exr"], 3, "maaf6_huge.exr"),
        case("isg-glossy and isg-dof inputs 3e38", ["filter", "isg-dof", "isg_huge.exr", "-o", "out.exr"], 0,
             creates=["out.exr"]),
        # --map forms.
        filter_("ratio --map ratio_u=myU reads myU.R/G/B", "ratio", "ratio_myU.exr", code=0, names="",
                extra_args=("--map", "ratio_u=myU"), creates=["out.exr"]),
        filter_("ratio --map ratio_u=nosuch", "ratio", "ratio.exr", names="nosuch.R",
                extra_args=("--map", "ratio_u=nosuch")),
        usage("--map without a channel", ["filter", "ratio", "ratio.exr", "-o", "out.exr", "--map", "ratio_u="],
              "--map"),
        usage("--map of an unknown role", ["filter", "gaussian", "good.exr", "-o", "out.exr", "--map", "colour=R"],
              "colour"),
        usage("--map with two channels for three", ["filter", "isg-shadow", "isg.exr", "-o", "out.exr", "--map",
                                                    "position=a,b"], "--map"),
        usage("--map without a role", ["filter", "maaf", "maaf.exr", "-o", "out.exr", "--map", "=P.X"], "--map"),
        # Exit codes of options.
        usage("analyze wedge --smin 1e-300 --smax 1e300 --gauss",
              ["analyze", "wedge", "--smin", "1e-300", "--smax", "1e300", "--gauss"], "--smin"),
        usage("analyze wedge --seed -1", ["analyze", "wedge", "--random", "2", "--grid", "16", "--seed", "-1"],
              "--seed"),
        usage("render --seed -1", ["render", "grids", "-o", "out.exr", *render8, "--seed", "-1"], "--seed"),
        usage("filter ratio --seed -1", ["filter", "ratio", "ratio.exr", "-o", "out.exr", "--seed", "-1"],
              "--seed"),
        usage("filter maaf --k 2 on a maaf6 render", ["filter", "maaf", "maaf6.exr", "-o", "out.exr", "--k", "2"],
              "maaf6.exr"),
        usage("render --aovs maaf6 --filter maaf --filter-param k=2",
              ["render", "grids", "-o", "out.exr", *render8, "--aovs", "maaf6", "--filter", "maaf",
               "--filter-param", "k=2"], "maaf6"),
        usage("render --filter isg-dof --filter-param aperture=-1",
              ["render", "grids", "-o", "out.exr", *render8, "--filter", "isg-dof", "--filter-param",
               "aperture=-1"], "aperture"),
        usage("render --aovs maaf6 --maaf6-effects bogus",
              ["render", "grids", "-o", "out.exr", *render8, "--aovs", "maaf6", "--maaf6-effects", "bogus"],
              "bogus"),
        usage("filter gaussian --sigma NaN", ["filter", "gaussian", "good.exr", "-o", "out.exr", "--sigma", "nan"],
              "nan"),
        # Options without effect are named in a warning.
        warn("render --maaf6-effects without the maaf6 group", ["--maaf6-effects", "shadows"], "--maaf6-effects"),
        warn("render --light-bandlimit without --adaptive", ["--light-bandlimit", "sigma"], "--light-bandlimit"),
        warn("render --pixel-footprint without --adaptive", ["--pixel-footprint", "receiver"], "--pixel-footprint"),
        # --light.
        filter_("isg-shadow --light of a missing file", "isg-shadow", "isg.exr", names="nosuch.json",
                extra_args=("--light", "nosuch.json")),
        filter_("maaf --light of garbage", "maaf", "maaf.exr", names="garbage.obj",
                extra_args=("--light", "garbage.obj")),
    ]


def aov_group_option_cases():
    """The options of the AOV groups' own parameters (--maaf-first-pass-spp, --maaf6-effects)."""
    render8 = ["render", "grids", "-o", "out.exr", "--width", "8", "--height", "8", "--spp", "1",
               "--progress", "none"]
    return [
        case("render --aovs maaf --maaf-first-pass-spp 0", [*render8, "--aovs", "maaf", "--maaf-first-pass-spp", "0"],
             2, "--maaf-first-pass-spp"),
        case("render --maaf-first-pass-spp 2.5", [*render8, "--aovs", "maaf", "--maaf-first-pass-spp", "2.5"], 2,
             "--maaf-first-pass-spp"),
        case("render --maaf-first-pass-spp not a number", [*render8, "--maaf-first-pass-spp", "many"], 2,
             "--maaf-first-pass-spp"),
        case("render --maaf-first-pass-spp without the maaf group", [*render8, "--maaf-first-pass-spp", "4"], 0,
             creates=["out.exr"], warns="--maaf-first-pass-spp has no effect without the maaf group"),
    ]


def plan_parameter_cases():
    """The plan's AAF parameters (aaf plan, render --adaptive) are checked by AAF's declarations."""
    def plan(name, args, option):
        return case(name, ["plan", "good.exr", "-o", "out.exr", *args], 2, option)

    def render(name, args, option):
        return case(name, RENDER + ["--adaptive", *args], 2, option)

    return [
        plan("plan --light-axes bogus", ["--light-axes", "bogus"], "--light-axes"),
        plan("plan --fill-radius 1.5", ["--fill-radius", "1.5"], "--fill-radius"),
        plan("plan --alpha 2", ["--alpha", "2"], "--alpha"),
        plan("plan --mu nan", ["--mu", "nan"], "--mu"),
        render("render --adaptive --light-bandlimit bogus", ["--light-bandlimit", "bogus"], "--light-bandlimit"),
        render("render --adaptive --pixel-footprint PROJECTED", ["--pixel-footprint", "PROJECTED"],
               "--pixel-footprint"),
        render("render --adaptive --mu inf", ["--mu", "inf"], "--mu"),
    ]


def main():
    shutil.rmtree(FILES, ignore_errors=True)
    os.makedirs(FILES)
    if len(sys.argv) == 3 and sys.argv[1] == "--templates":
        render_templates(sys.argv[2])
    write_images()
    write_scenes()
    write_temporal_files()
    write_method_inputs()
    cases = render_cases() + filter_cases() + other_cases() + fuzz_cases() + method_input_cases()
    cases += python_module_cases() + aaf_complete_cases() + slurm_filter_cases() + blender_bridge_cases()
    cases += temporal_sequence_cases() + render_filter_param_cases() + aov_group_option_cases()
    cases += plan_parameter_cases()
    names = [c["name"] for c in cases]
    if len(set(names)) != len(names):
        sys.exit("duplicate case names")
    with open(os.path.join(BAD, "cases.json"), "w") as f:
        json.dump({"about": "Written by scripts/make_bad_corpus.py; run by tests/bad_inputs/run_bad_inputs.py. "
                            "Paths are relative to a scratch copy of files/.", "cases": cases}, f, indent=1)
        f.write("\n")
    print("%d cases, %d files" % (len(cases), len(os.listdir(FILES))))


if __name__ == "__main__":
    main()
