"""Run by bridge_test.sh inside Blender (blender -b --factory-startup --python):
builds a shot by script (no .blend shipped): a floor, a tilted box occluder
and a sphere under a rectangular area light, seen by a camera; checks the
export of a depth-of-field camera; exports the shot with the aaf bridge
(scripts/blender/aaf_bridge.py) and renders it with Cycles, tiny, to a
multilayer EXR with Position, Normal and Object Index passes.
Arguments after --: BRIDGE_DIR OUT_DIR WIDTH HEIGHT."""
import json
import math
import os
import sys

import bpy

args = sys.argv[sys.argv.index("--") + 1:]
bridge_dir, out_dir, width, height = args[0], args[1], int(args[2]), int(args[3])
sys.path.insert(0, bridge_dir)
import aaf_bridge  # noqa: E402

bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
scene.name = "bridge"
scene.render.resolution_x, scene.render.resolution_y = width, height
scene.render.resolution_percentage = 100

bpy.ops.mesh.primitive_plane_add(size=4, location=(0, 0, 0))
bpy.ops.mesh.primitive_cube_add(size=0.5, location=(0.2, 0.1, 0.7), rotation=(0, 0, math.radians(30)))
bpy.ops.mesh.primitive_uv_sphere_add(radius=0.3, location=(-0.6, 0.3, 0.45), segments=16, ring_count=8)
bpy.ops.object.light_add(type="AREA", location=(0.3, -0.2, 2.5))
light = bpy.context.object
light.data.shape = "RECTANGLE"
light.data.size, light.data.size_y = 0.8, 0.5
light.data.energy = 200
bpy.ops.object.camera_add(location=(0, -4.0, 3.0), rotation=(math.radians(53), 0, 0))
camera = bpy.context.object
scene.camera = camera

# Depth of field: a thin lens with Cycles' aperture radius, focused on the plane given.
camera.data.dof.use_dof = True
camera.data.dof.focus_distance = 4.5
camera.data.dof.aperture_fstop = 2.0
warnings = []
exported = aaf_bridge.camera_json(scene, warnings)
assert exported["type"] == "thin_lens", exported
assert abs(exported["aperture_radius_m"] - camera.data.lens / 1000 / 4) < 1e-9, exported
assert abs(exported["focus_distance_m"] - 4.5) < 1e-9, exported
# 50 mm lens on a 36 mm sensor fitted to the width: tan(fov_y/2) = 18/50 * h/w.
expected_fov = math.degrees(2 * math.atan(18 / 50 * height / width))
assert abs(exported["fov_y_deg"] - expected_fov) < 1e-6, (exported, expected_fov)
camera.data.dof.use_dof = False  # the shot itself is in focus (AAF filters shadows)

command, warnings = aaf_bridge.export_scene(f"{out_dir}/shot.json", scene)
print("aaf-bridge-test: exported;", command, warnings)
document = json.load(open(f"{out_dir}/shot.json"))
assert len(document["objects"]) == 3 and len(document["lights"]) == 1, document
key = json.load(open(f"{out_dir}/shot.light.json"))
# The light emits downwards (Blender's -Z): edge_u x edge_v points down.
u, v = key["edge_u"], key["edge_v"]
assert u[0] * v[1] - u[1] * v[0] < 0, key
assert abs(math.hypot(*u) - 0.8) < 1e-6 and abs(math.hypot(*v) - 0.5) < 1e-6, key

scene.render.engine = "CYCLES"
scene.cycles.samples = 4
scene.cycles.use_denoising = False
layer = scene.view_layers[0]
layer.use_pass_position = True
layer.use_pass_normal = True
layer.use_pass_object_index = True
settings = scene.render.image_settings
settings.file_format = "OPEN_EXR_MULTILAYER"
settings.color_depth = "32"
scene.render.filepath = f"{out_dir}/cycles.exr"
bpy.ops.render.render(write_still=True)
print("aaf-bridge-test: view layer", layer.name, "rendered to", scene.render.filepath)
if len(args) > 4:  # the shot itself, for a test that exports it again (tests/docs/test_doc_commands.py)
    bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(args[4]))
