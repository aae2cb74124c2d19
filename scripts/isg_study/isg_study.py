#!/usr/bin/python3
"""Measures the ISG study's images (rendered and filtered by scripts/isg_study.sh).

usage: isg_study.py AAF WORK_DIR OUT_DIR SETTINGS

Each compared image is first written as a plain R,G,B EXR (the channels of
its effect), then measured with `aaf compare --metric rmse,flip` against the
effect's distribution-ray-traced reference. Writes OUT_DIR/isg_study.csv,
OUT_DIR/isg_study.md and OUT_DIR/contact_hardening.png."""
import csv
import os
import subprocess
import sys

import numpy as np
import OpenImageIO as oiio

aaf, work, out, settings = sys.argv[1:5]


def channels(path, names):
    image = oiio.ImageInput.open(path)
    if image is None:
        sys.exit(f"isg_study.py: cannot open {path}")
    spec = image.spec()
    pixels = image.read_image(0, spec.nchannels, "float")
    image.close()
    index = {name: i for i, name in enumerate(spec.channelnames)}
    missing = [n for n in names if n not in index]
    if missing:
        sys.exit(f"isg_study.py: {path} lacks {missing}")
    return np.stack([pixels[:, :, index[n]] for n in names], axis=2)


def write_rgb(name, rgb):
    path = os.path.join(work, name + ".exr")
    spec = oiio.ImageSpec(rgb.shape[1], rgb.shape[0], rgb.shape[2], "float")
    spec.channelnames = ("R", "G", "B") if rgb.shape[2] == 3 else ("Y",)
    writer = oiio.ImageOutput.create(path)
    writer.open(path, spec)
    writer.write_image(np.ascontiguousarray(rgb, dtype=np.float32))
    writer.close()
    return path


def rgb(file, layer=None):
    names = ["R", "G", "B"] if layer is None else [layer + c for c in (".R", ".G", ".B")]
    return channels(os.path.join(work, file), names)


def compare(test, reference, mask=None):
    csv_path = os.path.join(work, "compare.csv")
    command = [aaf, "compare", test, reference, "--metric", "rmse,flip", "--csv", csv_path]
    if mask:
        command += ["--mask", mask]
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
    with open(csv_path) as f:
        row = list(csv.DictReader(f))[-1]
    return float(row["rmse"]), float(row["flip"])


def shadow_input(file):
    unshadowed = rgb(file, "unshadowed")
    return unshadowed * channels(os.path.join(work, file), ["isg.V"])


rows = []  # effect, image, rays per pixel, rmse, flip


def measure(effect, label, rays, image, reference, mask=None):
    test = write_rgb(f"{effect}_{len(rows)}", image)
    rmse, flip = compare(test, reference, mask)
    rows.append((effect, label, rays, rmse, flip))


ref_spp = settings.split("references ")[1].split(" spp")[0]
aaf_spp = settings.split("AAF ")[1].split(" spp")[0]

shadow_ref = write_rgb("shadow_ref", rgb("ref.exr"))
measure("soft shadows", "ISG isg-shadow (hard-shadow input)", "1", rgb("isg_shadow.exr"), shadow_ref)
for n in (9, 81):
    measure("soft shadows", f"ISG isg-shadow, {n} search and {n} gather samples", "1",
            rgb(f"isg_shadow_{n}.exr"), shadow_ref)
for option, file in (("--sigma 0.0001", "sigma_1e-4"), ("--sigma 0.01", "sigma_1e-2"),
                     ("--light-shape disk", "disk"), ("--pattern stratified", "stratified")):
    measure("soft shadows", f"ISG isg-shadow {option}", "1", rgb(f"isg_shadow_{file}.exr"), shadow_ref)
measure("soft shadows", "input: hard shadow, one ray to the light's centre", "1", shadow_input("one.exr"), shadow_ref)
measure("soft shadows", "input: distribution ray tracing, 1 spp", "1", rgb("one.exr"), shadow_ref)
measure("soft shadows", "AAF (CLI defaults), 1 spp", "1", rgb("aaf_one.exr"), shadow_ref)
measure("soft shadows", f"AAF (CLI defaults), {aaf_spp} spp", aaf_spp, rgb("aaf.exr"), shadow_ref)
measure("soft shadows", f"distribution ray tracing, {aaf_spp} spp, unfiltered", aaf_spp, rgb("aaf_in.exr"), shadow_ref)

glossy_ref = write_rgb("glossy_ref", rgb("ref.exr", "glossy"))
glossy_mask = write_rgb("glossy_mask", (channels(os.path.join(work, "ref.exr"), ["gloss.theta_max"]) > 0)
                        .astype(np.float32))
measure("glossy reflection", "ISG isg-glossy (mirror input)", "1", rgb("isg_glossy.exr", "isg_glossy"), glossy_ref,
        glossy_mask)
for n in (9, 81):
    measure("glossy reflection", f"ISG isg-glossy, {n} search and {n} gather samples", "1",
            rgb(f"isg_glossy_{n}.exr", "isg_glossy"), glossy_ref, glossy_mask)
measure("glossy reflection", "ISG isg-glossy --spatial-weight gaussian", "1",
        rgb("isg_glossy_gaussian.exr", "isg_glossy"), glossy_ref, glossy_mask)
measure("glossy reflection", "input: mirror reflection map", "1", rgb("one.exr", "reflect"), glossy_ref, glossy_mask)
measure("glossy reflection", "input: cone-sampled glossy ray, 1 spp", "1", rgb("one.exr", "glossy"), glossy_ref,
        glossy_mask)

dof_ref = write_rgb("dof_ref", rgb("lens.exr"))
measure("depth of field", "ISG isg-dof (pinhole input)", "1", rgb("isg_dof.exr", "isg_dof"), dof_ref)
for n in (9, 81):
    measure("depth of field", f"ISG isg-dof, {n} search and {n} gather samples", "1",
            rgb(f"isg_dof_{n}.exr", "isg_dof"), dof_ref)
measure("depth of field", "input: pinhole image", "1", rgb("lens.exr", "pinhole"), dof_ref)
measure("depth of field", "input: thin-lens ray tracing, 1 spp", "1", rgb("lens_one.exr"), dof_ref)

os.makedirs(out, exist_ok=True)
with open(os.path.join(out, "isg_study.csv"), "w", newline="") as f:
    writer = csv.writer(f)
    writer.writerow(["effect", "image", "rays_per_pixel", "rmse", "flip_mean"])
    for row in rows:
        writer.writerow([row[0], row[1], row[2], f"{row[3]:.6f}", f"{row[4]:.6f}"])
with open(os.path.join(out, "isg_study.md"), "w") as f:
    f.write(f"Settings: {settings}. Error against each effect's distribution-ray-traced reference "
            f"({ref_spp} spp); glossy over the glossy pixels only (theta_max > 0). "
            "Produced by scripts/isg_study.sh.\n\n")
    f.write("Machine: " + subprocess.run([os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "machine.sh")],
                                         capture_output=True, text=True, check=True).stdout.strip() + ".\n\n")
    f.write("| effect | image | rays/pixel for the effect | RMSE | FLIP (mean) |\n| --- | --- | --- | --- | --- |\n")
    for row in rows:
        f.write(f"| {row[0]} | {row[1]} | {row[2]} | {row[3]:.5f} | {row[4]:.4f} |\n")

# Contact hardening: the hard-shadow input, ISG and the reference side by side.
panels = []
for name, image in (("hard", shadow_input("one.exr")), ("isg", rgb("isg_shadow.exr")), ("ref", rgb("ref.exr"))):
    exr = write_rgb("panel_" + name, image)
    png = os.path.join(work, "panel_" + name + ".png")
    subprocess.run([aaf, "preview", exr, "-o", png], check=True, stdout=subprocess.DEVNULL)
    panel = oiio.ImageInput.open(png)
    panels.append(panel.read_image(0, 3, "uint8"))
    panel.close()


def write_png(name, pixels):
    path = os.path.join(out, name)
    writer = oiio.ImageOutput.create(path)
    writer.open(path, oiio.ImageSpec(pixels.shape[1], pixels.shape[0], 3, "uint8"))
    writer.write_image(np.ascontiguousarray(pixels))
    writer.close()


write_png("contact_hardening.png", np.concatenate(panels, axis=1))
# The post's shadow on the floor, 3x (nearest): hard input, ISG, reference from top to bottom.
h, w = panels[0].shape[:2]
rows, cols = slice(int(0.54 * h), int(0.70 * h)), slice(int(0.06 * w), int(0.38 * w))
closeup = np.concatenate([p[rows, cols] for p in panels], axis=0)
write_png("contact_hardening_closeup.png", closeup.repeat(3, axis=0).repeat(3, axis=1))
print(open(os.path.join(out, "isg_study.md")).read())
