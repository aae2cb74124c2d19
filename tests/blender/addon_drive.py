"""Run by addon_test.sh inside Blender (blender -b --factory-startup --python):
installs and enables the aaf bridge as an add-on, sets its preferences and
drives its panel's operators on a shot built by script.
Arguments after --: BRIDGE AAF WORK_DIR WIDTH HEIGHT METHODS MODE
  METHODS  the methods `aaf filter --help` lists, comma-separated
  MODE     drive: every step, the panel, cancelling a render;
           bad-path: the preferences name no executable, then run_all;
           bad-option: export and render, then filter with an option aaf refuses.
A failing mode exits Blender by the add-on itself (aaf's code); the shell
checks the code and the error line."""
import filecmp
import math
import os
import shutil
import sys
import time

import bpy

args = sys.argv[sys.argv.index("--") + 1:]
bridge, aaf, work, width, height, methods, mode = \
    args[0], args[1], args[2], int(args[3]), int(args[4]), args[5].split(","), args[6]


def check(condition, message):
    if not condition:
        print("aaf-addon-test: FAILED:", message)
        sys.stdout.flush()
        sys.exit(1)


# Installed as an artist installs it (Edit > Preferences > Add-ons > Install);
# BLENDER_USER_SCRIPTS points into the scratch folder.
bpy.ops.preferences.addon_install(filepath=bridge, overwrite=True)
bpy.ops.preferences.addon_enable(module="aaf_bridge")
addon = sys.modules["aaf_bridge"]
check(os.path.realpath(addon.__file__).startswith(os.path.realpath(work)),
      f"the add-on was installed to {addon.__file__}, outside the scratch folder")
preferences = bpy.context.preferences.addons["aaf_bridge"].preferences
preferences.aaf_path = os.path.join(work, "nosuch", "aaf") if mode == "bad-path" else aaf

scene = bpy.context.scene
for obj in list(bpy.data.objects):  # the factory scene's cube, point light and camera
    bpy.data.objects.remove(obj)
scene.render.resolution_x, scene.render.resolution_y = width, height
scene.render.resolution_percentage = 100
bpy.ops.mesh.primitive_plane_add(size=4, location=(0, 0, 0))
bpy.ops.mesh.primitive_cube_add(size=0.5, location=(0.2, 0.1, 0.7), rotation=(0, 0, math.radians(30)))
cube = bpy.context.object
subdivision = cube.modifiers.new("subdivision", "SUBSURF")
subdivision.levels, subdivision.render_levels = 0, 1  # Cycles renders 24 quads, the viewport 6
bpy.ops.object.light_add(type="AREA", location=(0.3, -0.2, 2.5))
bpy.context.object.data.size = 0.8
bpy.ops.object.camera_add(location=(0, -4.0, 3.0), rotation=(math.radians(53), 0, 0))
scene.camera = bpy.context.object
settings = scene.aaf
if mode == "drive":  # the default shot path is beside the .blend file, which is not saved
    try:
        addon.shot_paths(scene)
        check(False, f"an unsaved file's shot went to {addon.shot_paths(scene)[0]}")
    except addon.StepError as e:
        check(e.code == 3 and "not saved" in str(e), f"an unsaved file's shot path: {e}")
out = os.path.join(work, mode)
settings.shot_path = os.path.join(out, "shot.json")
settings.spp = 8
shot, aovs, filtered = addon.shot_paths(scene)
check((shot, aovs, filtered) == tuple(os.path.join(out, n) for n in
                                      ("shot.json", "shot.aovs.exr", "shot.filtered.exr")),
      f"the shot's files are {shot}, {aovs}, {filtered}")

if mode == "bad-path":
    bpy.ops.aaf.run_all()
    check(False, "run_all with a bad aaf path returned")
if mode == "bad-option":
    bpy.ops.aaf.export_shot()
    bpy.ops.aaf.render()
    settings.filter_options = "--mu -1"
    bpy.ops.aaf.filter()
    check(False, "a filter aaf refuses returned")


class Layout:
    """Stands in for Blender's UILayout (there is none headless): records what
    a draw function shows and checks that each property and operator exists."""

    def __init__(self, shown):
        self.shown = shown

    def __getattr__(self, name):  # use_property_split and the like
        return None

    def __setattr__(self, name, value):
        object.__setattr__(self, name, value)

    def row(self, **kwargs):
        return Layout(self.shown)

    column = box = split = row

    def prop(self, data, name, **kwargs):
        check(name in data.bl_rna.properties, f"the panel draws {name}, which {data} has not")
        self.shown.append(name)

    def operator(self, idname, **kwargs):
        category, name = idname.split(".")
        check(hasattr(bpy.types, category.upper() + "_OT_" + name), f"no operator {idname}")
        self.shown.append(idname)

    def label(self, **kwargs):
        self.shown.append("label: " + kwargs.get("text", ""))

    def separator(self, **kwargs):
        pass


def drawn(draw, **fields):
    """What `draw` shows, called as Blender calls it on a panel or preferences with these fields."""
    shown = []
    draw(type("Drawn", (), dict(fields, layout=Layout(shown)))(), bpy.context)
    return shown


# The panel: registered in the Render properties, drawing every setting and step.
panel = getattr(bpy.types, "RENDER_PT_aaf", None)
check(panel is not None and panel.bl_space_type == "PROPERTIES" and panel.bl_context == "render",
      "no panel RENDER_PT_aaf in the Render properties")
shown = drawn(panel.draw)
for expected in ("shot_path", "method", "spp", "filter_options", "aaf.export_shot", "aaf.render",
                 "aaf.filter", "aaf.load_result", "aaf.run_all"):
    check(expected in shown, f"the panel does not show {expected} (it shows {shown})")


class Running:
    status = "aaf render"


addon._running = Running()  # while a step runs, the panel shows its progress
shown = drawn(panel.draw)
addon._running = None
check("aaf_progress" in shown, f"a running step's progress is not shown ({shown})")
shown = drawn(addon.AafPreferences.draw, aaf_path=preferences.aaf_path, bl_rna=preferences.bl_rna)
check("aaf_path" in shown and "label: Runs " + aaf in shown, f"the preferences show {shown}")

# The method enum is the list `aaf filter --help` gives.
items = [item[0] for item in addon._method_items(settings, bpy.context)]
check(items == methods, f"the method enum is {items}, aaf filter --help lists {methods}")
for method in methods:
    settings.method = method
    check(settings.method == method, f"method {method} cannot be chosen")
try:
    settings.method = "nosuch"
    check(False, "an unknown method was accepted")
except TypeError:
    pass
settings.method = "aaf"

# Each step's operator, as the panel's buttons run them.
selected = sorted(o.name for o in bpy.context.selected_objects)
check(bpy.ops.aaf.export_shot() == {"FINISHED"} and os.path.isfile(shot) and
      os.path.isfile(os.path.join(out, "shot.light.json")), "export")
with open(os.path.join(out, "shot_meshes", "001_Cube.obj")) as obj:
    triangles = sum(1 for line in obj if line.startswith("f "))
check(triangles == 48, f"the cube was exported with {triangles} triangles, Cycles renders 48")
check([m.name for m in cube.modifiers] == ["subdivision"] and len(bpy.data.scenes) == 1 and
      sorted(o.name for o in bpy.context.selected_objects) == selected, "the export changed the scene")
check(bpy.ops.aaf.render() == {"FINISHED"} and os.path.isfile(aovs), "render")
check(bpy.ops.aaf.filter() == {"FINISHED"} and os.path.isfile(filtered), "filter")
check(bpy.ops.aaf.load_result() == {"FINISHED"}, "load")
tree = scene.node_tree
images = [n for n in tree.nodes if n.type == "IMAGE"]
check(len(images) == 1 and os.path.samefile(bpy.path.abspath(images[0].image.filepath), filtered),
      f"the compositor shows {[n.image.filepath for n in images]}, not {filtered}")
passes = [socket.name for socket in images[0].outputs]
for name in ("Combined", "aaf", "aaf_beta", "noisy"):
    check(name in passes, f"the compositor has no pass {name} ({passes})")
composite = next(n for n in tree.nodes if n.type == "COMPOSITE")
check(any(link.from_socket == images[0].outputs["Combined"] and link.to_node == composite
          for link in tree.links), "the Combined pass is not linked to the Composite node")
# What the compositor makes of it, for the shell to compare with aaf's file.
shutil.copy(filtered, os.path.join(work, "filtered_aaf.exr"))
scene.render.engine = "CYCLES"
scene.cycles.samples = 1
scene.cycles.use_denoising = False
scene.render.use_compositing = True
scene.render.image_settings.file_format = "OPEN_EXR"
scene.render.image_settings.color_depth = "32"
scene.render.filepath = os.path.join(work, "blender_Combined.exr")
bpy.ops.render.render(write_still=True)

# Cancelling a render (Esc in the modal operator calls Pipeline.cancel):
# aaf stops, the checkpoint it writes is removed and the earlier render stays.
settings.spp = 1 << 20  # aaf's most, about a minute at this size
listing, before = sorted(os.listdir(out)), open(aovs, "rb").read()
pipeline = addon.Pipeline(scene, ("render",))
job = pipeline.job
deadline = time.time() + 20
while not pipeline.tick() and pipeline.progress == 0 and time.time() < deadline:
    time.sleep(0.05)
    job = pipeline.job
progress = pipeline.progress
check(0 < progress < 1, f"no progress reported within 20 s (progress {progress})")
pipeline.cancel()
check(job.process.returncode is not None, "aaf still runs after cancel")
check(sorted(os.listdir(out)) == listing, f"cancel left {sorted(set(os.listdir(out)) - set(listing))}")
check(open(aovs, "rb").read() == before, "cancel changed the earlier render")
print("aaf-addon-test: cancelled at", f"{100 * progress:.0f} %;", "aaf said:", job.lines[-1:])
settings.spp = 8

# Everything in one go with another method: the compositor's node shows the new file's layers.
settings.method = "gaussian"
check(bpy.ops.aaf.run_all() == {"FINISHED"}, "run_all")
images = [n for n in tree.nodes if n.type == "IMAGE"]
passes = [socket.name for socket in images[0].outputs]
check(len(images) == 1, f"loading again added a node ({len(images)} image nodes)")
check("aaf" in passes and "aaf_beta" not in passes,
      f"the compositor still shows the earlier file's passes after run_all with gaussian ({passes})")
check(not filecmp.cmp(filtered, os.path.join(work, "filtered_aaf.exr"), shallow=False),
      "run_all with gaussian did not write a new filtered render")
print("aaf-addon-test: OK: panel, preferences, export, render, filter, load, cancel and run_all")
