#!/usr/bin/python3
"""Every command of the README and the method pages runs, as written.

Usage: test_doc_commands.py AAF_EXECUTABLE SOURCE_DIR WORK_DIR

Reads each page's ```sh blocks and runs their lines in order with bash, in
a scratch folder per page where `aaf` is the built executable and
`scripts/` the repository's, and fails on the first line that exits non-zero
(naming the page and line, with its output). Files a page uses before any of
its commands makes them (another renderer's EXR, a light file, a Blender
shot, references) are made first, by the fixtures below. Two things are
changed, and only these: `aaf render` lines that give no --width/--height
get a small size (the page's), so the whole run takes about a minute; and
the README's set-up lines (`./scripts/demo.sh`, `./scripts/test.sh`) are
not run here, as this test is part of the second and the first takes
minutes (CI runs it separately). Blender's lines need Blender
(scripts/install_blender.sh, which scripts/test.sh runs)."""
import json
import os
import re
import shlex
import shutil
import subprocess
import sys

aaf_exe, source_dir, work_dir = sys.argv[1], os.path.abspath(sys.argv[2]), os.path.abspath(sys.argv[3])
setup_lines = {"./scripts/demo.sh", "./scripts/test.sh"}
# Each page's render size where a line gives none (the README's crop needs 300x250).
page_sizes = {"README.md": (360, 270)}
default_size = (96, 72)


def blocks(text):
    """Each ```sh block's (first line number, [(line number, command)])."""
    for block in re.finditer(r"^```sh\n(.*?)^```", text, re.S | re.M):
        first = text.count("\n", 0, block.start(1)) + 1
        commands, pending, start = [], "", None
        for offset, line in enumerate(block.group(1).split("\n")):
            start = first + offset if start is None else start
            pending += line
            if pending.endswith("\\"):
                pending = pending[:-1] + " "
                continue
            command = re.sub(r"\s+#.*$", "", pending).strip()
            if command and not command.startswith("#"):
                commands.append((start, command))
            pending, start = "", None
        yield first, commands


def sized(command, size):
    words = shlex.split(command)
    if words[:2] == ["aaf", "render"] and "--list" not in words and "--width" not in words:
        return command + f" --width {size[0]} --height {size[1]}"
    return command


def run(command, cwd, env, where):
    done = subprocess.run(["bash", "-c", command], cwd=cwd, env=env, capture_output=True, text=True, timeout=600)
    if done.returncode != 0:
        print(f"{where}: exit {done.returncode}: {command}\n{done.stdout[-3000:]}{done.stderr[-3000:]}")
        sys.exit(1)


def fixture_renderer_file(cwd, env, size):
    """cycles.exr as another renderer writes it: AAF's inputs, position as Pw, no light in the header."""
    w, h = size
    run(f"aaf render grids --aovs aaf --spp 4 --width {w} --height {h} -o grids.exr --progress none", cwd, env,
        "fixture")
    script = """
import sys, OpenImageIO as oiio
src = oiio.ImageBuf(sys.argv[1])
spec = src.spec()
names = [n.replace("P.", "Pw.", 1) if n.startswith("P.") else n for n in spec.channelnames]
out = oiio.ImageBuf(spec)
out.copy_pixels(src)
out.specmod().channelnames = names
for attribute in [a.name for a in spec.extra_attribs if a.name.startswith("aaf:")]:
    out.specmod().erase_attribute(attribute)
out.write(sys.argv[2])
"""
    subprocess.run(["/usr/bin/python3", "-c", script, "grids.exr", "cycles.exr"], cwd=cwd, check=True)
    scene = json.load(open(os.path.join(source_dir, "testdata/scenes/grids.json")))
    json.dump(scene["lights"][0], open(os.path.join(cwd, "shot.light.json"), "w"))


def fixture_blender_shot(cwd, env, size):
    """shot.blend, and its Cycles render cycles.exr at the README's 960x540 (the bridge test's shot)."""
    blender = shutil.which("blender")
    if not blender:
        print("FAILED: the README's Blender lines need Blender: run scripts/install_blender.sh")
        sys.exit(1)
    scene = os.path.join(source_dir, "tests/blender/bridge_scene.py")
    run(f"{shlex.quote(blender)} -b --factory-startup --python-exit-code 1 --python {shlex.quote(scene)} -- "
        f"{shlex.quote(os.path.join(source_dir, 'scripts/blender'))} . 960 540 shot.blend", cwd, env, "fixture")


def fixture_references(cwd, env, size):
    """What the README compares against: a reference, a reference sequence, two folders, frames 101-124."""
    w, h = size
    quiet = f"--width {w} --height {h} --progress none"
    for command in [f"aaf render grids -o reference.exr --spp 64 {quiet}",
                    f"aaf render grids --frames 1-24 -o 'ref.####.exr' --spp 16 {quiet}",
                    f"aaf render grids --frames 101-124 -o 'noisy.####.exr' --aovs aaf --spp 9 {quiet}",
                    "mkdir -p test_dir ref_dir && cp aaf.0001.exr aaf.0002.exr test_dir/ && cp aaf.0001.exr aaf.0002.exr ref_dir/"]:
        run(command, cwd, env, "fixture")


def fixture_lens_scene(cwd, env, size):
    scene = json.load(open(os.path.join(source_dir, "testdata/scenes/gallery.json")))
    scene["name"] = "gallery_lens"
    scene["camera"].update({"type": "thin_lens", "aperture_radius_m": 0.15, "focus_distance_m": 4.6})
    json.dump(scene, open(os.path.join(cwd, "lens.json"), "w"))


def fixture_ratio_reference(cwd, env, size):
    w, h = size
    run(f"aaf render livingroom --aovs ratio --spp 32 --seed 1000 --width {w} --height {h} -o ref.exr --progress none",
        cwd, env, "fixture")


# (page, a line the block starts with) -> what that block needs made first.
fixtures = {
    ("README.md", "aaf info cycles.exr"): fixture_renderer_file,
    ("README.md", "blender -b shot.blend"): fixture_blender_shot,
    ("README.md", "aaf compare filtered.exr reference.exr"): fixture_references,
    ("libaaf/core/methods/isg/README.md", "aaf render gallery"): fixture_lens_scene,
    ("libaaf/core/methods/ratio/README.md", "aaf render livingroom"): fixture_ratio_reference,
}

pages = ["README.md"] + sorted(os.path.relpath(os.path.join(d, "README.md"), source_dir)
                               for d in [os.path.join(source_dir, "libaaf/core/methods", m)
                                         for m in os.listdir(os.path.join(source_dir, "libaaf/core/methods"))]
                               if os.path.isfile(os.path.join(d, "README.md")))
bin_dir = os.path.join(work_dir, "bin")
os.makedirs(bin_dir, exist_ok=True)
if not os.path.exists(os.path.join(bin_dir, "aaf")):
    os.symlink(os.path.abspath(aaf_exe), os.path.join(bin_dir, "aaf"))
env = dict(os.environ, PATH=bin_dir + os.pathsep + os.environ["PATH"])
count = 0
for page in pages:
    text = open(os.path.join(source_dir, page)).read()
    cwd = os.path.join(work_dir, page.replace("/", "_"))
    shutil.rmtree(cwd, ignore_errors=True)
    os.makedirs(cwd)
    os.symlink(os.path.join(os.path.abspath(source_dir), "scripts"), os.path.join(cwd, "scripts"))
    size = page_sizes.get(page, default_size)
    for first, commands in blocks(text):
        for (_, command) in commands[:1]:
            for (fixture_page, start), make in fixtures.items():
                if fixture_page == page and command.startswith(start):
                    make(cwd, env, size)
        for line, command in commands:
            if command in setup_lines:
                continue
            run(sized(command, size), cwd, env, f"{page}:{line}")
            count += 1
print(f"{count} commands of {len(pages)} pages ran")
