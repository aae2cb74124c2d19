"""A Cycles shot with two lights and indirect light, a fixture for work on
light groups (tests/blender/cycles_key_light_test.sh runs it at 8 and 1024 samples):

  blender -b --factory-startup --python-exit-code 1 \\
    --python tests/blender/cycles_two_lights_scene.py -- OUT_DIR AAF [NOISY_SPP REFERENCE_SPP [FRAMES]]

Builds by script (no .blend shipped) a floor, a red wall beside it (the
indirect light: the floor near the wall turns red) and a box casting a soft
shadow of the key light, a 1 x 0.6 m area light named Key, plus a second,
smaller area light named Second lighting the box from the side. The view layer has a light group `key`
holding the key light alone. Cycles renders it at 64 x 48 into two
multilayer EXRs with the passes Combined, the `key` light group, Diffuse
Color, Normal and Depth: OUT_DIR/noisy.exr (NOISY_SPP, default 8 samples per
pixel) and OUT_DIR/reference.exr (REFERENCE_SPP, default 4096; same seed,
no denoising, no adaptive sampling). It prints every channel name of the
files and, on a line of its own, the light group's. Then it exports the shot
with the aaf bridge (OUT_DIR/shot.json, shot.light.json: the key light is
the first area light by name), renders aaf's AOVs of it (`AAF render
--aovs all`, OUT_DIR/shot.aovs.exr) and completes the noisy render with them
(scripts/blender/aaf_complete.py, OUT_DIR/noisy.completed.exr).

With FRAMES, a sequence instead: the camera slides sideways over frames
1-FRAMES, the Vector pass (motion) is on, Cycles draws each frame with its
own seed, and every file above is per frame (noisy.####.exr,
reference.####.exr, shot.####.json, shot.aovs.####.exr,
noisy.completed.####.exr; one shot.light.json, the lights do not move).
aaf's AOVs are rendered with `--aovs aaf`, without aaf's own motion layer:
the completed frames' motion is Blender's Vector pass."""
import json
import math
import os
import subprocess
import sys
import time

import bpy
import mathutils
import OpenImageIO as oiio

args = sys.argv[sys.argv.index("--") + 1:]
if len(args) not in (2, 4, 5):
    print("usage: blender -b --python cycles_two_lights_scene.py -- OUT_DIR AAF [NOISY_SPP REFERENCE_SPP [FRAMES]]",
          file=sys.stderr)
    sys.exit(2)
out_dir, aaf = os.path.abspath(args[0]), args[1]
noisy_spp, reference_spp = (int(args[2]), int(args[3])) if len(args) >= 4 else (8, 4096)
frames = int(args[4]) if len(args) == 5 else 0
scripts = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts", "blender")
sys.path.insert(0, scripts)
import aaf_bridge  # noqa: E402

WIDTH, HEIGHT = 64, 48
os.makedirs(out_dir, exist_ok=True)
bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
scene.name = "two_lights"


def diffuse(name, colour):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    material.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (*colour, 1)
    return material


def add(operator, material, **kwargs):
    operator(**kwargs)
    obj = bpy.context.object
    obj.data.materials.append(material)
    return obj


add(bpy.ops.mesh.primitive_plane_add, diffuse("floor", (0.8, 0.8, 0.8)), size=6, location=(0, 0, 0))
add(bpy.ops.mesh.primitive_cube_add, diffuse("wall", (0.8, 0.1, 0.05)), size=1,
    location=(-1.6, 0.5, 1.0), scale=(0.05, 2.5, 1.0))
box = add(bpy.ops.mesh.primitive_cube_add, diffuse("box", (0.7, 0.7, 0.7)), size=0.6,
          location=(0.2, 0.4, 0.9), rotation=(0, 0, math.radians(25)))

bpy.ops.object.light_add(type="AREA", location=(0.4, 0.2, 2.6))
key = bpy.context.object
key.name = "Key"
key.data.shape, key.data.size, key.data.size_y = "RECTANGLE", 1.0, 0.6
key.data.energy = 80
bpy.ops.object.light_add(type="AREA", location=(2.2, -1.0, 1.6))
second = bpy.context.object
second.name = "Second"
second.data.size = 0.3
second.data.energy = 25
# Facing the box: an area light emits along its -Z.
second.rotation_euler = (box.location - second.location).to_track_quat("-Z", "Y").to_euler()

bpy.ops.object.camera_add(location=(0.8, -4.0, 2.4), rotation=(math.radians(66), 0, math.radians(12)))
scene.camera = bpy.context.object

layer = scene.view_layers[0]
layer.lightgroups.add(name="key")
key.lightgroup = "key"
layer.use_pass_combined = True
layer.use_pass_diffuse_color = True
layer.use_pass_normal = True
layer.use_pass_z = True

scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.use_denoising = False
scene.cycles.use_adaptive_sampling = False
scene.cycles.seed = 1
scene.render.resolution_x, scene.render.resolution_y = WIDTH, HEIGHT
scene.render.resolution_percentage = 100
settings = scene.render.image_settings
settings.file_format = "OPEN_EXR_MULTILAYER"
settings.color_depth = "32"


def render(name, spp):
    scene.cycles.samples = spp
    scene.render.filepath = os.path.join(out_dir, name)
    start = time.time()
    bpy.ops.render.render(write_still=True)
    print(f"two-lights: {name}: {spp} spp in {time.time() - start:.1f} s")




def render_sequence():
    """The camera slides 6 cm to the right per frame (about a pixel); every file per frame."""
    camera = scene.camera
    start_x = camera.location.x
    for frame in (1, frames):
        camera.location.x = start_x + 0.06 * (frame - 1)
        camera.keyframe_insert("location", frame=frame)
    for curve in camera.animation_data.action.fcurves:
        for point in curve.keyframe_points:
            point.interpolation = "LINEAR"
    layer.use_pass_vector = True
    scene.cycles.use_animated_seed = True
    for frame in range(1, frames + 1):
        scene.frame_set(frame)
        render(f"noisy.{frame:04d}.exr", noisy_spp)
        render(f"reference.{frame:04d}.exr", reference_spp)
        shot = os.path.join(out_dir, f"shot.{frame:04d}.json")
        _, warnings = aaf_bridge.export_scene(shot, scene)
        for warning in warnings:
            print("two-lights: bridge warning:", warning)
        aovs = os.path.join(out_dir, f"shot.aovs.{frame:04d}.exr")
        subprocess.run([aaf, "render", shot, "--width", str(WIDTH), "--height", str(HEIGHT), "--aovs", "aaf",
                        "--spp", "64", "--progress", "none", "-o", aovs], check=True)
        subprocess.run(["/usr/bin/python3", os.path.join(scripts, "aaf_complete.py"),
                        os.path.join(out_dir, f"noisy.{frame:04d}.exr"), aovs,
                        os.path.join(out_dir, f"noisy.completed.{frame:04d}.exr")], check=True)
    print(f"two-lights: wrote frames 1-{frames} to {out_dir}")


if frames:
    render_sequence()
    sys.exit(0)
render("noisy.exr", noisy_spp)
render("reference.exr", reference_spp)

image = oiio.ImageInput.open(os.path.join(out_dir, "noisy.exr"))
channels = list(image.spec().channelnames)
image.close()
print("two-lights: channels:", " ".join(channels))
print("two-lights: light group 'key' channels:", " ".join(c for c in channels if "key" in c))

command, warnings = aaf_bridge.export_scene(os.path.join(out_dir, "shot.json"), scene)
for warning in warnings:
    print("two-lights: bridge warning:", warning)
with open(os.path.join(out_dir, "shot.light.json")) as exported:
    exported_key = json.load(exported)
if (key.location - mathutils.Vector(exported_key["center"])).length > 1e-6:
    print(f"two-lights: error: the bridge exported the light at {exported_key['center']} as the key light",
          file=sys.stderr)
    sys.exit(1)
aovs = os.path.join(out_dir, "shot.aovs.exr")
subprocess.run([aaf, "render", os.path.join(out_dir, "shot.json"), "--width", str(WIDTH), "--height",
                str(HEIGHT), "--aovs", "all", "--spp", "64", "--progress", "none", "-o", aovs], check=True)
subprocess.run(["/usr/bin/python3", os.path.join(scripts, "aaf_complete.py"), os.path.join(out_dir, "noisy.exr"),
                aovs, os.path.join(out_dir, "noisy.completed.exr")], check=True)
print("two-lights: wrote", ", ".join(os.path.join(out_dir, n) for n in
                                      ("noisy.exr", "reference.exr", "shot.json", "shot.light.json",
                                       "shot.aovs.exr", "noisy.completed.exr")))
