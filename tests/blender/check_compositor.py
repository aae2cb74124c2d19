"""Run by compositor_test.sh inside Blender (blender -b --python):
opens a filtered aaf output as a multilayer image in the compositor, checks
that the layers appear as passes with the expected names, and writes the
passes to check (given after --) through a Composite node to EXR files,
whose pixels the shell script compares with the aaf output's channels."""
import sys

import bpy

args = sys.argv[sys.argv.index("--") + 1:]
image_path, out_dir, expected = args[0], args[1], args[2].split(",")
width, height = int(args[3]), int(args[4])  # a multilayer image reports size 0 until composited
image = bpy.data.images.load(image_path)

scene = bpy.context.scene
scene.render.engine = "CYCLES"  # renders on the CPU, headless
scene.cycles.samples = 1
scene.render.resolution_x, scene.render.resolution_y = width, height
scene.render.resolution_percentage = 100
scene.render.use_compositing = True
scene.render.image_settings.file_format = "OPEN_EXR"
scene.render.image_settings.color_depth = "32"
scene.use_nodes = True
tree = scene.node_tree
for node in list(tree.nodes):
    tree.nodes.remove(node)
source = tree.nodes.new("CompositorNodeImage")
source.image = image
composite = tree.nodes.new("CompositorNodeComposite")

passes = [socket.name for socket in source.outputs]
print("aaf-check: passes", passes)
missing = [name for name in expected if name not in passes]
if missing:
    print("aaf-check: FAILED: passes missing from the compositor:", missing)
    sys.exit(1)
if image.type != "MULTILAYER":
    # Blender 3.4 reports a file it splits into passes as a multilayer image.
    print("aaf-check: note: image type", image.type)
for name in expected:
    for link in list(tree.links):
        tree.links.remove(link)
    tree.links.new(source.outputs[name], composite.inputs["Image"])
    scene.render.filepath = f"{out_dir}/blender_{name}.exr"
    bpy.ops.render.render(write_still=True)
print("aaf-check: wrote", ", ".join(expected))
