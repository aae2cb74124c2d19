#!/usr/bin/python3
"""The Python module does what the CLI does with the same inputs: multi-part
files, --light, every missing input in one error, any path type, typed
defaults, progress and cancelling, and non-EXR inputs refused.

Usage: test_cli_parity.py AAF_EXECUTABLE SCRATCH_DIR (PYTHONPATH must find `aaf`)."""
import json
import os
import pathlib
import shutil
import struct
import subprocess
import sys
import unittest
import zlib

import numpy as np

import aaf

AAF_EXE, SCRATCH = sys.argv[1], sys.argv[2]
LIGHT_ATTRIBUTES = ("aaf:light:center", "aaf:light:normal", "aaf:light:axis_u", "aaf:light:axis_v",
                    "aaf:light:width_m", "aaf:light:height_m", "aaf:light:sigma_m", "aaf:light:kind")


def scratch(name):
    return os.path.join(SCRATCH, name)


def setUpModule():
    shutil.rmtree(SCRATCH, ignore_errors=True)
    os.makedirs(SCRATCH)
    subprocess.run([AAF_EXE, "render", "grids", "-o", scratch("noisy.exr"), "--width", "40", "--height", "30",
                    "--spp", "4"], check=True)


def cli_error(*args):
    """The CLI's one error line for `aaf ARGS`, less its "aaf: error: " prefix; asserts exit 3."""
    run = subprocess.run([AAF_EXE] + list(args), capture_output=True, text=True)
    assert run.returncode == 3, (args, run.returncode, run.stderr)
    lines = [line for line in run.stderr.splitlines() if line.startswith("aaf: error: ")]
    assert len(lines) == 1, run.stderr
    return lines[0][len("aaf: error: "):]


def without(aovs, channels=(), attributes=()):
    return aaf.Aovs({k: v for k, v in aovs.channels.items() if k not in channels},
                    {k: v for k, v in aovs.attributes.items() if k not in attributes})


def assert_same_channels(test, a, b):
    test.assertEqual(sorted(a.channels), sorted(b.channels))
    for name in a.channels:
        test.assertTrue(np.array_equal(a.channels[name], b.channels[name], equal_nan=True), name)


class BytesPath(os.PathLike):
    """An os.PathLike whose os.fspath is bytes, as os.DirEntry of a bytes scandir gives."""

    def __init__(self, path):
        self.path = os.fsencode(path)

    def __fspath__(self):
        return self.path


class MultiPart(unittest.TestCase):
    def test_every_part_of_a_lossy_cli_output_is_read_and_filters_again(self):
        # dwaa puts the colour channels in one part and the data channels (visibility, P, N) in another.
        lossy, lossless = scratch("filtered_dwaa.exr"), scratch("filtered_zip.exr")
        for out, extra in ((lossy, ["--compression", "dwaa"]), (lossless, [])):
            subprocess.run([AAF_EXE, "filter", "aaf", scratch("noisy.exr"), "-o", out] + extra, check=True)
        parts = aaf.read(lossy)
        whole = aaf.read(lossless)
        self.assertEqual(sorted(parts.channels), sorted(whole.channels))
        # The data part is lossless: its channels come back bit for bit.
        for name in ("shadow.V", "P.X", "N.X", "aaf.V"):
            if name in whole.channels:
                self.assertTrue(np.array_equal(parts.channels[name], whole.channels[name]), name)
        self.assertIn("shadow.V", parts.channels)
        refiltered = aaf.filter("aaf", parts)
        self.assertIn("aaf.V", refiltered.channels)


class Compose(unittest.TestCase):
    def test_compose_gives_the_cli_compose_result_and_a_bad_value_is_refused(self):
        noisy = aaf.read(scratch("noisy.exr"))
        for compose in ("correct", "paper"):
            out = scratch("compose_%s.exr" % compose)
            subprocess.run([AAF_EXE, "filter", "aaf", scratch("noisy.exr"), "-o", out, "--compose", compose],
                           check=True)
            assert_same_channels(self, aaf.filter("aaf", noisy, compose=compose), aaf.read(out))
        with self.assertRaisesRegex(aaf.Error, "compose"):
            aaf.filter("aaf", noisy, compose="recomposed")


class Light(unittest.TestCase):
    def light_file(self, aovs, shift_m):
        """A light object file (scene format) of the render's key light moved by `shift_m` along its normal."""
        a = aovs.attributes
        center = np.add(a["aaf:light:center"], np.multiply(a["aaf:light:normal"], shift_m))
        light = {"center": list(map(float, center)),
                 "edge_u": [float(x) * a["aaf:light:width_m"] for x in a["aaf:light:axis_u"]],
                 "edge_v": [float(x) * a["aaf:light:height_m"] for x in a["aaf:light:axis_v"]],
                 "profile": a["aaf:light:kind"], "sigma_m": a["aaf:light:sigma_m"]}
        path = pathlib.Path(scratch("moved.light.json"))
        path.write_text(json.dumps(light))
        return path

    def test_light_gives_a_headerless_frame_the_cli_light_result(self):
        noisy = aaf.read(scratch("noisy.exr"))
        headerless = without(noisy, attributes=LIGHT_ATTRIBUTES)
        aaf.write(scratch("headerless.exr"), headerless)
        light = self.light_file(noisy, 0.5)
        with self.assertRaisesRegex(aaf.InputError, "aaf:light:center"):
            aaf.filter("aaf", headerless)
        py = aaf.filter("aaf", headerless, light=light, threads=1)
        out = scratch("headerless_cli.exr")
        subprocess.run([AAF_EXE, "filter", "aaf", scratch("headerless.exr"), "-o", out, "--light", str(light)],
                       check=True)
        assert_same_channels(self, py, aaf.read(out))
        # The light file replaces a header light too: a moved light filters differently.
        own = aaf.filter("aaf", noisy, threads=1)
        moved = aaf.filter("aaf", noisy, light=light, threads=1)
        self.assertFalse(np.array_equal(own.channels["aaf.V"], moved.channels["aaf.V"]))
        self.assertTrue(np.array_equal(moved.channels["aaf.V"], py.channels["aaf.V"]))

    def test_a_bad_light_file_raises_input_error_naming_it(self):
        bad = scratch("bad.light.json")
        with open(bad, "w") as f:
            f.write("{\"center\": [0, 0]}")
        with self.assertRaises(aaf.InputError) as caught:
            aaf.filter("aaf", aaf.read(scratch("noisy.exr")), light=bad)
        self.assertIn("bad.light.json", str(caught.exception))


class MissingInputs(unittest.TestCase):
    def test_a_frame_missing_two_inputs_raises_one_error_naming_both_as_the_cli(self):
        lacking = without(aaf.read(scratch("noisy.exr")), channels=("shadow.V",), attributes=LIGHT_ATTRIBUTES)
        aaf.write(scratch("lacking.exr"), lacking)
        with self.assertRaises(aaf.InputError) as caught:
            aaf.filter("aaf", lacking)
        message = str(caught.exception)
        self.assertIn("missing 2 inputs", message)
        self.assertIn("visibility", message)
        self.assertIn("aaf:light:center", message)
        cli = cli_error("filter", "aaf", scratch("lacking.exr"), "-o", scratch("lacking_out.exr"))
        self.assertEqual(cli, scratch("lacking.exr") + ": " + message)


class Paths(unittest.TestCase):
    def test_every_path_argument_takes_str_pathlib_and_bytes_path_likes(self):
        noisy = aaf.read(scratch("noisy.exr"))
        for kind, make in (("str", str), ("pathlib", pathlib.Path), ("bytes", BytesPath)):
            out = scratch("path_%s.exr" % kind)
            aaf.write(make(out), noisy)
            back = aaf.read(make(out))
            assert_same_channels(self, back, noisy)
            self.assertEqual(aaf.compare(make(out), make(scratch("noisy.exr")))["mse"], 0.0, kind)
            light = Light.light_file(self, noisy, 0.0)
            filtered = aaf.filter("aaf", noisy, light=make(light), threads=1)
            self.assertIn("aaf.V", filtered.channels, kind)
        odd = BytesPath(os.fsencode(scratch("caf")) + b"\xe9.exr")  # a file name that is not UTF-8
        aaf.write(odd, noisy)
        self.assertTrue(os.path.exists(odd.path))
        assert_same_channels(self, aaf.read(odd), noisy)

    def test_a_path_of_another_type_is_refused_naming_the_argument(self):
        with self.assertRaisesRegex(aaf.Error, "light: expected a path"):
            aaf.filter("aaf", aaf.read(scratch("noisy.exr")), light=3)


class Defaults(unittest.TestCase):
    TYPES = {"float": float, "int": int, "bool": bool, "choice": str, "text": str}

    def test_defaults_have_their_parameters_type_and_pass_back_as_keywords(self):
        noisy = aaf.read(scratch("noisy.exr"))
        mu = [p for p in aaf.method("aaf")["parameters"] if p["name"] == "mu"][0]
        self.assertIs(type(mu["default"]), float)
        self.assertEqual(mu["default"], 2.0)
        for method in aaf.methods():
            for p in method["parameters"]:
                self.assertIs(type(p["default"]), self.TYPES[p["type"]], (method["name"], p["name"]))
        # Each method's defaults given back as keywords change nothing.
        for name in ("aaf", "gaussian"):
            defaults = {p["name"]: p["default"] for p in aaf.method(name)["parameters"]}
            assert_same_channels(self, aaf.filter(name, noisy, threads=1, **defaults),
                                 aaf.filter(name, noisy, threads=1))


class Progress(unittest.TestCase):
    def test_progress_is_called_with_fractions_that_never_decrease_and_end_at_one(self):
        fractions = []
        filtered = aaf.filter("aaf", aaf.read(scratch("noisy.exr")), progress=fractions.append)
        self.assertIn("aaf.V", filtered.channels)
        self.assertGreaterEqual(len(fractions), 3)
        self.assertTrue(all(0.0 <= f <= 1.0 for f in fractions), fractions)
        self.assertEqual(fractions, sorted(fractions))
        self.assertLess(fractions[0], 1.0)
        self.assertEqual(fractions[-1], 1.0)

    def test_false_cancels_with_aaf_cancelled_and_nothing_is_returned_or_written(self):
        noisy = aaf.read(scratch("noisy.exr"))
        calls = []

        def stop_at_half(fraction):
            calls.append(fraction)
            return fraction < 0.5

        out = scratch("cancelled.exr")
        with self.assertRaises(aaf.Cancelled):
            aaf.write(out, aaf.filter("aaf", noisy, progress=stop_at_half))
        self.assertTrue(issubclass(aaf.Cancelled, aaf.Error))
        self.assertFalse(os.path.exists(out))
        self.assertNotIn(1.0, calls)
        # None goes on: a callable that returns nothing does not cancel.
        self.assertIn("aaf.V", aaf.filter("aaf", noisy, progress=lambda f: None).channels)

    def test_an_exception_in_the_callback_cancels_and_is_raised_itself(self):
        class Stop(Exception):
            pass

        def fail(fraction):
            raise Stop("at %g" % fraction)

        with self.assertRaises(Stop):
            aaf.filter("aaf", aaf.read(scratch("noisy.exr")), progress=fail)

    def test_a_progress_that_is_not_callable_is_refused(self):
        with self.assertRaisesRegex(aaf.Error, "progress: expected a callable"):
            aaf.filter("aaf", aaf.read(scratch("noisy.exr")), progress=0.5)


def png_bytes(width, height):
    """A minimal 8-bit grey PNG (the PNG spec's chunks: IHDR, IDAT, IEND)."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    rows = b"".join(b"\x00" + bytes(range(width)) for _ in range(height))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))


class Formats(unittest.TestCase):
    def test_a_png_is_refused_naming_the_file_even_named_exr(self):
        for name in ("picture.png", "picture_named.exr"):
            path = scratch(name)
            with open(path, "wb") as f:
                f.write(png_bytes(4, 3))
            with self.assertRaises(aaf.InputError) as caught:
                aaf.read(path)
            self.assertIn(path + ": not an AOV EXR (a PNG image", str(caught.exception))

    def test_a_text_file_is_refused_as_not_openexr(self):
        path = scratch("notes.exr")
        with open(path, "w") as f:
            f.write("not an image\n")
        with self.assertRaisesRegex(aaf.InputError, "notes.exr: not an AOV EXR"):
            aaf.read(path)


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
