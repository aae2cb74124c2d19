#!/usr/bin/python3
"""The Python module `aaf` against the CLI and the library's contracts.

Usage: test_module.py AAF_EXECUTABLE SCRATCH_DIR (PYTHONPATH must find `aaf`)."""
import math
import os
import shutil
import subprocess
import sys
import unittest

import numpy as np

import aaf

AAF_EXE, SCRATCH = sys.argv[1], sys.argv[2]


def scratch(name):
    return os.path.join(SCRATCH, name)


def setUpModule():
    shutil.rmtree(SCRATCH, ignore_errors=True)
    os.makedirs(SCRATCH)
    subprocess.run([AAF_EXE, "render", "grids", "-o", scratch("noisy.exr"), "--width", "40", "--height", "30",
                    "--spp", "4"], check=True)


class ReadWrite(unittest.TestCase):
    def test_round_trip_keeps_every_channel_value_and_attribute(self):
        aovs = aaf.read(scratch("noisy.exr"))
        self.assertIn("R", aovs.channels)
        self.assertEqual(aovs.channels["R"].dtype, np.float32)
        self.assertEqual(aovs.channels["R"].shape, (30, 40))
        aaf.write(scratch("copy.exr"), aovs)
        back = aaf.read(scratch("copy.exr"))
        self.assertEqual(list(back.channels), list(aovs.channels))
        for name, array in aovs.channels.items():
            self.assertTrue(np.array_equal(array, back.channels[name]), name)
        for name in ("aaf:light:center", "aaf:light:width_m", "aaf:seed", "aaf:light:kind"):
            self.assertEqual(back.attributes[name], aovs.attributes[name], name)
        self.assertEqual(len(aovs.attributes["aaf:light:center"]), 3)

    def test_arrays_built_in_python_are_written_as_given(self):
        ramp = np.arange(12, dtype=np.float64).reshape(3, 4) / 7  # float64 is converted
        aaf.write(scratch("ramp.exr"), aaf.Aovs({"Y": ramp}, {"note": "hi", "n": 3, "v": (1.0, 2.0, 3.0)}))
        back = aaf.read(scratch("ramp.exr"))
        self.assertTrue(np.array_equal(back.channels["Y"], ramp.astype(np.float32)))
        self.assertEqual(back.channels["Y"][2, 3], np.float32(11 / 7))  # row-major: [y, x]
        self.assertEqual((back.attributes["note"], back.attributes["n"], back.attributes["v"]),
                         ("hi", 3, (1.0, 2.0, 3.0)))


class Methods(unittest.TestCase):
    def test_every_registered_method_is_listed_with_roles_and_parameters(self):
        names = [m["name"] for m in aaf.methods()]
        self.assertIn("aaf", names)
        self.assertIn("gaussian", names)
        described = aaf.method("aaf")
        self.assertIn("visibility", described["required"])
        mu = [p for p in described["parameters"] if p["name"] == "mu"][0]
        self.assertEqual((mu["type"], mu["default"]), ("float", 2.0))
        for name in names:  # the filter docstring is generated from the same registry
            self.assertIn("  " + name + ": ", aaf.filter.__doc__)

    def test_parameters_and_defaults_are_the_command_lines_and_the_plan_shares_aafs(self):
        def helped(*words):
            run = subprocess.run([AAF_EXE] + list(words) + ["--help"], capture_output=True, text=True)
            self.assertEqual(run.returncode, 0, words)
            return " ".join(run.stdout.split())

        def option(p):
            name = "--" + p["name"].replace("_", "-")
            if p["type"] == "bool":
                return name + " "
            # The help shows a float default as its shortest decimal: 2, 0.001.
            default = ("%.9g" % p["default"]) if p["type"] == "float" else p["default"]
            return "%s %s=%s " % (name, {"float": "FLOAT", "int": "INT"}.get(p["type"], "TEXT"), default)

        for method in [m["name"] for m in aaf.methods()]:
            text = helped("filter", method)
            for p in aaf.method(method)["parameters"]:
                self.assertIn(option(p), text, (method, p["name"]))
        # One declaration: the plan's (aaf plan, render --adaptive) are AAF's own.
        shared = {p["name"]: p for p in aaf.method("aaf")["parameters"]}
        for command in (("plan",), ("render",)):
            text = helped(*command)
            for name in ("mu", "light_bandlimit", "light_axes", "pixel_footprint"):
                self.assertIn(option(shared[name]), text, (command, name))

    def test_a_method_run_equals_the_cli_output_for_every_method(self):
        aovs = aaf.read(scratch("noisy.exr"))
        runs = {"aaf": (["--mu", "3", "--filter", "2d"], {"mu": 3, "filter": "2d"}),
                "gaussian": (["--sigma", "1.5"], {"sigma": 1.5})}
        for method in [m["name"] for m in aaf.methods()]:
            args, kwargs = runs.get(method, ([], {}))
            out = scratch("cli_%s.exr" % method)
            run = subprocess.run([AAF_EXE, "filter", method, scratch("noisy.exr"), "-o", out] + args)
            if run.returncode == 3:  # inputs this render lacks: the module refuses them too
                with self.assertRaises(aaf.InputError, msg=method):
                    aaf.filter(method, aovs, **kwargs)
                continue
            self.assertEqual(run.returncode, 0, method)
            cli = aaf.read(out)
            py = aaf.filter(method, aovs, threads=1, **kwargs)
            # The same channels (an EXR file stores them in its own order).
            self.assertEqual(sorted(py.channels), sorted(cli.channels), method)
            for name in cli.channels:
                self.assertTrue(np.array_equal(py.channels[name], cli.channels[name]), (method, name))

    def test_a_render_made_for_a_delegate_is_filtered_by_the_plan_aaf_filter_makes(self):
        # `aaf filter aaf` hands a combined-effects render to maaf6 --pairs 1 (a note says so);
        # the module runs the same prepared plan, so the same method and pixels.
        render, out = scratch("combined.exr"), scratch("combined_aaf.exr")
        subprocess.run([AAF_EXE, "render", "room", "-o", render, "--aovs", "maaf6", "--width", "24",
                        "--height", "18", "--spp", "4"], check=True)
        run = subprocess.run([AAF_EXE, "filter", "aaf", render, "-o", out], capture_output=True, text=True)
        self.assertEqual(run.returncode, 0, run.stderr)
        self.assertEqual(run.stderr.count("aaf: note: "), 1)
        self.assertIn("aaf filter maaf6 --pairs 1", run.stderr)
        cli = aaf.read(out)
        py = aaf.filter("aaf", aaf.read(render), threads=1)
        self.assertEqual(sorted(py.channels), sorted(cli.channels))
        for name in cli.channels:
            self.assertTrue(np.array_equal(py.channels[name], cli.channels[name]), name)

    def test_map_renames_a_role_as_the_cli_map_does(self):
        aovs = aaf.read(scratch("noisy.exr"))
        renamed = aaf.Aovs({("vis.Y" if k == "shadow.V" else k): v for k, v in aovs.channels.items()},
                           aovs.attributes)
        with self.assertRaises(aaf.InputError):
            aaf.filter("aaf", renamed)
        a = aaf.filter("aaf", aovs)
        b = aaf.filter("aaf", renamed, map={"visibility": "vis.Y"})
        self.assertTrue(np.array_equal(a.channels["aaf.V"], b.channels["aaf.V"]))


class Compare(unittest.TestCase):
    def test_arrays_and_files_give_the_cli_numbers(self):
        noisy = aaf.read(scratch("noisy.exr"))
        filtered = aaf.filter("aaf", noisy)
        aaf.write(scratch("f.exr"), filtered)
        from_files = aaf.compare(scratch("f.exr"), scratch("noisy.exr"), metrics=["rmse", "mse", "psnr"])
        from_arrays = aaf.compare(filtered, noisy, metrics=["rmse", "mse", "psnr"])
        for key in ("rmse", "mse", "psnr", "pixels"):
            self.assertEqual(from_files[key], from_arrays[key], key)
        r, g, b = (filtered.channels[c].astype(np.float64) - noisy.channels[c] for c in "RGB")
        mse = float(np.mean(np.stack([r, g, b]) ** 2))
        self.assertAlmostEqual(from_arrays["mse"], mse, delta=1e-9 + 1e-6 * mse)
        self.assertAlmostEqual(from_arrays["psnr"], 10 * math.log10(1.0 / mse), places=6)
        self.assertEqual(from_arrays["psnr_peak"], 1.0)
        cli = subprocess.run([AAF_EXE, "compare", scratch("f.exr"), scratch("noisy.exr"), "--json"],
                             check=True, capture_output=True, text=True).stdout
        import json
        self.assertAlmostEqual(json.loads(cli)["rmse"], from_files["rmse"], places=12)

    def test_identical_images_have_zero_error_and_infinite_psnr(self):
        noisy = aaf.read(scratch("noisy.exr"))
        result = aaf.compare(noisy, noisy)
        self.assertEqual(result["mse"], 0.0)
        self.assertEqual(result["psnr"], math.inf)


class Errors(unittest.TestCase):
    def test_a_missing_file_raises_input_error_naming_it(self):
        with self.assertRaises(aaf.InputError) as caught:
            aaf.read(scratch("no_such.exr"))
        self.assertIn("no_such.exr", str(caught.exception))
        self.assertTrue(issubclass(aaf.InputError, aaf.Error))

    def test_a_missing_channel_of_a_compared_file_names_the_file(self):
        aaf.write(scratch("only_y.exr"), aaf.Aovs({"Y": np.zeros((2, 2))}))
        with self.assertRaises(aaf.InputError) as caught:
            aaf.compare(scratch("only_y.exr"), scratch("only_y.exr"))
        self.assertIn("only_y.exr", str(caught.exception))

    def test_bad_parameters_and_methods_raise_error_naming_them(self):
        aovs = aaf.read(scratch("noisy.exr"))
        with self.assertRaisesRegex(aaf.Error, "mu"):
            aaf.filter("aaf", aovs, mu=0)
        with self.assertRaisesRegex(aaf.Error, "no_such_parameter"):
            aaf.filter("aaf", aovs, no_such_parameter=1)
        with self.assertRaisesRegex(aaf.Error, "nosuch"):
            aaf.filter("nosuch", aovs)

    def test_arrays_of_different_shapes_are_refused_naming_the_channel(self):
        with self.assertRaisesRegex(aaf.Error, "'G'"):
            aaf.write(scratch("bad.exr"), aaf.Aovs({"R": np.zeros((2, 2)), "G": np.zeros((3, 2))}))
        self.assertFalse(os.path.exists(scratch("bad.exr")))

    def test_an_unwritable_output_raises_input_error_naming_it(self):
        with self.assertRaises(aaf.InputError) as caught:
            aaf.write(scratch("no_dir/out.exr"), aaf.Aovs({"Y": np.zeros((2, 2))}))
        self.assertIn("no_dir/out.exr", str(caught.exception))


class InstructionSets(unittest.TestCase):
    def test_a_pinned_instruction_set_gives_the_cli_bytes_under_the_same_pin(self):
        aovs = aaf.read(scratch("noisy.exr"))
        before = aaf.instruction_set()
        try:
            aaf.set_instruction_set("sse4.2")
            self.assertEqual(aaf.instruction_set(), "sse4.2")
            out = scratch("cli_sse42.exr")
            subprocess.run([AAF_EXE, "filter", "aaf", scratch("noisy.exr"), "-o", out, "--isa", "sse4.2"],
                           check=True)
            py = aaf.filter("aaf", aovs)
            for name, array in aaf.read(out).channels.items():
                self.assertTrue(np.array_equal(py.channels[name], array), name)
        finally:
            aaf.set_instruction_set(before)

    def test_an_unknown_instruction_set_raises_error_naming_it(self):
        with self.assertRaises(aaf.Error) as caught:
            aaf.set_instruction_set("avx9000")
        self.assertIn("avx9000", str(caught.exception))


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
