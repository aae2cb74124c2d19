#!/usr/bin/python3
"""Every bad argument of the module `aaf` raises aaf.Error (or its subclass
aaf.InputError) naming the argument, as the CLI refuses the same input with
a usage or input error: never pybind11's "Unable to cast" RuntimeError, a
TypeError, or a silently different file. Nothing is written on failure.

Usage: test_bad_arguments.py SCRATCH_DIR (PYTHONPATH must find `aaf`)."""
import math
import os
import pathlib
import shutil
import sys
import unittest

import numpy as np

import aaf

SCRATCH = sys.argv[1]
Y = np.zeros((2, 2), np.float32)
RGB = {"R": Y, "G": Y, "B": Y}


def scratch(name):
    return os.path.join(SCRATCH, name)


def setUpModule():
    shutil.rmtree(SCRATCH, ignore_errors=True)
    os.makedirs(SCRATCH)


class BadArguments(unittest.TestCase):
    def refused(self, call, named, kind=aaf.Error):
        """`call` raises `kind` naming `named` and leaves the scratch folder empty."""
        with self.assertRaises(kind) as caught:
            call()
        self.assertIn(named, str(caught.exception))
        self.assertEqual(os.listdir(SCRATCH), [], "a refused call left a file")
        return str(caught.exception)

    def test_an_int_attribute_beyond_32_bits_is_refused_naming_it(self):
        self.refused(lambda: aaf.write(scratch("o.exr"), aaf.Aovs({"Y": Y}, {"frame_id": 2 ** 40})), "frame_id")
        self.refused(lambda: aaf.write(scratch("o.exr"), aaf.Aovs({"Y": Y}, {"big": 10 ** 400})), "big")

    def test_a_float_attribute_beyond_32_bit_floats_is_refused(self):
        self.refused(lambda: aaf.write(scratch("o.exr"), aaf.Aovs({"Y": Y}, {"far": 1e300})), "far")
        self.refused(lambda: aaf.write(scratch("o.exr"), aaf.Aovs({"Y": Y}, {"v": (1.0, 1e300, 0.0)})), "'v'")
        self.refused(lambda: aaf.write(scratch("o.exr"), aaf.Aovs({"Y": Y}, {"v": (1, "a", 2)})), "'v'")

    def test_names_that_are_not_str_are_refused(self):
        self.refused(lambda: aaf.write(scratch("o.exr"), aaf.Aovs({1: Y})), "channel name")
        self.refused(lambda: aaf.write(scratch("o.exr"), aaf.Aovs({"Y": Y}, {3: 1})), "attribute name")
        self.refused(lambda: aaf.filter("aaf", aaf.Aovs({"Y": Y}), map={1: "Y"}), "map")

    def test_an_empty_channel_name_is_refused_not_read_back_as_another(self):
        self.refused(lambda: aaf.write(scratch("o.exr"), aaf.Aovs({"": Y, "G": Y})), "channel ''")
        self.refused(lambda: aaf.filter("gaussian", aaf.Aovs({**RGB, "": Y})), "channel ''")

    def test_compare_refuses_a_peak_the_cli_refuses(self):
        a = aaf.Aovs(RGB)
        for peak in (0, -1.0, math.nan, math.inf):
            self.refused(lambda: aaf.compare(a, a, peak=peak), "peak")
        self.refused(lambda: aaf.compare(a, a, peak="1"), "peak")
        self.assertEqual(aaf.compare(a, a, peak=2.0)["psnr_peak"], 2.0)

    def test_write_refuses_a_name_of_another_image_format(self):
        for name in ("o.png", "o.JPG", "o.tif"):
            self.refused(lambda: aaf.write(scratch(name), aaf.Aovs({"Y": Y})), name)
        aaf.write(pathlib.Path(scratch("o.exr")), aaf.Aovs({"Y": Y}))  # an os.PathLike is a path
        self.assertTrue(np.array_equal(aaf.read(scratch("o.exr")).channels["Y"], Y))
        os.remove(scratch("o.exr"))

    def test_a_failed_allocation_is_reported_as_out_of_memory(self):
        # A 4 TB float32 copy of a broadcast view: no machine allocates it.
        huge = np.broadcast_to(np.float64(1.0), (1000000, 1000000))
        message = self.refused(lambda: aaf.write(scratch("o.exr"), aaf.Aovs({"Y": huge})), "'Y'")
        self.assertIn("out of memory", message)
        self.assertNotIn("not an array of numbers", message)

    def test_arrays_that_are_not_images_of_numbers_are_refused_naming_the_channel(self):
        for bad in ([["a"]], np.zeros((2, 2), complex), np.zeros((0, 3)), np.zeros((2, 2, 2)), None):
            self.refused(lambda: aaf.write(scratch("o.exr"), aaf.Aovs({"Y": bad})), "'Y'")

    def test_arguments_of_the_wrong_type_raise_aaf_error_naming_them(self):
        a = aaf.Aovs({"Y": Y})
        self.refused(lambda: aaf.read(5), "path")
        self.refused(lambda: aaf.write(scratch("o.exr"), 5), "aovs")
        self.refused(lambda: aaf.write(5, a), "path")
        self.refused(lambda: aaf.write(scratch("o.exr"), a, compression=3), "compression")
        self.refused(lambda: aaf.write(scratch("o.exr"), a, half="yes"), "half")
        self.refused(lambda: aaf.write(scratch("o.exr"), a, compression="bogus"), "bogus", aaf.InputError)
        self.refused(lambda: aaf.Aovs(5), "channels")
        self.refused(lambda: aaf.Aovs({"Y": Y}, 5), "attributes")
        with self.assertRaisesRegex(aaf.Error, "channels"):
            a.channels = 5
        self.refused(lambda: aaf.method(3), "name")
        self.refused(lambda: aaf.filter(3, a), "method")
        self.refused(lambda: aaf.filter("gaussian", 5), "aovs")
        self.refused(lambda: aaf.filter("gaussian", aaf.Aovs(RGB), threads=2 ** 40), "threads")
        self.refused(lambda: aaf.filter("gaussian", aaf.Aovs(RGB), threads=-1), "threads")
        self.refused(lambda: aaf.filter("gaussian", aaf.Aovs(RGB), sigma=None), "sigma")
        self.refused(lambda: aaf.filter("gaussian", aaf.Aovs(RGB), sigma=10 ** 400), "sigma")
        self.refused(lambda: aaf.compare("a.exr", a), "test")
        self.refused(lambda: aaf.compare(a, a, metrics=[3]), "metrics")
        self.refused(lambda: aaf.compare(a, a, metrics=["bogus"]), "bogus")
        self.refused(lambda: aaf.compare(a, a, channels=5), "channels")
        self.refused(lambda: aaf.compare(a, a, layer=None), "layer")


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
