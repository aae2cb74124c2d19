"""aaf bridge for Blender 3.4: export the active scene to aaf's JSON scene
format (libaaf/SCENE_FORMAT.md) so that `aaf render` produces every AOV for
the same shot, and read aaf's outputs back into the compositor.

As an add-on (Edit > Preferences > Add-ons > Install, this file): File >
Export > "aaf scene (.json)", and the operator "aaf: load outputs into the
compositor" (F3 search).

Headless (Debian's blender, scripts/install_blender.sh):

  blender -b shot.blend --python scripts/blender/aaf_bridge.py -- export OUT.json
  blender -b shot.blend --python scripts/blender/aaf_bridge.py -- load FILTERED.exr

`export` writes OUT.json (meshes as OBJ files under OUT_meshes/, with their
world transforms applied; the camera with its depth of field; every area
light, the first one the key light), OUT.light.json (the key light alone,
for `aaf filter --light` on a Cycles render of the same shot; OUT is the
path less .json) and prints the
`aaf render` command with the scene's resolution; everything is written into
a temporary folder beside OUT.json first and renamed into place, so a failed
export leaves nothing behind. `load` puts the file in an Image node of the
compositor, its Combined pass into the Composite node.

A failure is one line `aaf-bridge: error: ...` on stderr and aaf's exit code:
2 usage, 3 a scene that cannot be exported or a file that cannot be read or
written, 1 anything else.

What is exported and what is not (libaaf/RENDERERS.md "Blender"): mesh objects
(evaluated: modifiers applied), their material's Principled BSDF base colour
as albedo (0.75 without one); perspective cameras (sensor fit and shift-free
framing; Blender's shift is not exported); area lights (square, rectangle; a
disk or an ellipse as the rectangle around it, with a warning), emitting
uniformly, intensity = power / pi W/sr. Point, spot and sun lights, curves,
volumes and textures are skipped with a warning.
"""
import json
import math
import os
import shutil
import sys
import tempfile

import bpy
import mathutils

bl_info = {
    "name": "aaf bridge",
    "author": "libaaf",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "File > Export > aaf scene (.json); F3: aaf: load outputs",
    "description": "Export the scene for aaf render; load aaf's filtered EXRs into the compositor",
    "category": "Import-Export",
}


class UsageError(Exception):
    """A command line the bridge does not understand (exit 2)."""


class InputError(RuntimeError):
    """A scene that cannot be exported, or a file that cannot be read or written (exit 3)."""


def _vec(v):
    return [float(v[0]), float(v[1]), float(v[2])]


def _albedo(obj):
    """The base colour of the object's first material's Principled BSDF, else 0.75."""
    for slot in obj.material_slots:
        material = slot.material
        if material is None or not material.use_nodes:
            continue
        for node in material.node_tree.nodes:
            if node.type == "BSDF_PRINCIPLED":
                c = node.inputs["Base Color"].default_value
                return [float(c[0]), float(c[1]), float(c[2])]
    return 0.75


def _write_obj(obj, depsgraph, path):
    """The evaluated mesh of `obj`, triangulated, in world coordinates."""
    evaluated = obj.evaluated_get(depsgraph)
    mesh = evaluated.to_mesh()
    mesh.calc_loop_triangles()
    world = obj.matrix_world
    with open(path, "w") as out:
        out.write(f"# {obj.name} exported by aaf_bridge.py, world coordinates, metres\n")
        for vertex in mesh.vertices:
            p = world @ vertex.co
            out.write(f"v {p.x:.9g} {p.y:.9g} {p.z:.9g}\n")
        for triangle in mesh.loop_triangles:
            a, b, c = (i + 1 for i in triangle.vertices)
            out.write(f"f {a} {b} {c}\n")
    count = len(mesh.loop_triangles)
    evaluated.to_mesh_clear()
    return count


def camera_json(scene, warnings):
    """The scene camera as aaf's camera object (world coordinates as Blender's)."""
    cam = scene.camera
    if cam is None or cam.type != "CAMERA":
        raise InputError("the scene has no camera")
    data = cam.data
    if data.type != "PERSP":
        raise InputError(f"camera '{cam.name}': only perspective cameras can be exported")
    if data.shift_x or data.shift_y:
        warnings.append(f"camera '{cam.name}': lens shift is not exported")
    width, height = image_size(scene)
    world = cam.matrix_world
    position = world.translation
    forward = (world.to_3x3() @ mathutils.Vector((0, 0, -1))).normalized()
    up = (world.to_3x3() @ mathutils.Vector((0, 1, 0))).normalized()
    # Blender fits the sensor to the wider side (AUTO) or the side it is told.
    fit = data.sensor_fit
    if fit == "AUTO":
        fit = "HORIZONTAL" if width >= height else "VERTICAL"
        sensor = data.sensor_width
    else:
        sensor = data.sensor_width if fit == "HORIZONTAL" else data.sensor_height
    half = math.atan(sensor / (2.0 * data.lens))
    if fit == "HORIZONTAL":
        half = math.atan(math.tan(half) * height / width)
    camera = {"position": _vec(position), "up": _vec(up), "fov_y_deg": math.degrees(2.0 * half)}
    focus_m = 1.0
    if data.dof.use_dof:
        if data.dof.focus_object is not None:
            focus_m = (data.dof.focus_object.matrix_world.translation - position).dot(forward)
        else:
            focus_m = data.dof.focus_distance
        # Cycles' aperture radius: focal length / (2 f-stop), millimetres to metres.
        camera["type"] = "thin_lens"
        camera["aperture_radius_m"] = data.lens / 1000.0 / (2.0 * data.dof.aperture_fstop)
        camera["focus_distance_m"] = focus_m
    camera["look_at"] = _vec(position + forward * focus_m)
    return camera


def light_json(obj, warnings):
    """An area light as aaf's light object: it emits along its local -Z, as Blender's does."""
    data = obj.data
    world = obj.matrix_world
    axes = world.to_3x3()
    size_x = data.size
    size_y = data.size_y if data.shape in ("RECTANGLE", "ELLIPSE") else data.size
    if data.shape in ("DISK", "ELLIPSE"):
        warnings.append(f"light '{obj.name}': a {data.shape.lower()} is exported as the rectangle around it")
    edge_u = axes @ mathutils.Vector((size_x, 0, 0))
    edge_v = axes @ mathutils.Vector((0, -size_y, 0))  # u x v = -Z, the emitting side
    return {
        "center": _vec(world.translation),
        "edge_u": _vec(edge_u),
        "edge_v": _vec(edge_v),
        "profile": "uniform",
        "intensity": float(data.energy) / math.pi,
        "color": _vec(data.color),
    }


def image_size(scene):
    scale = scene.render.resolution_percentage / 100.0
    return int(scene.render.resolution_x * scale), int(scene.render.resolution_y * scale)


def export_scene(path, scene=None):
    """Writes the scene to `path` (aaf's JSON), its meshes to PATH_meshes/ and
    the key light to PATH.light.json; returns (the aaf render command, the
    warnings). Raises InputError, and writes nothing, when the scene cannot
    be exported or the files cannot be written."""
    scene = scene or bpy.context.scene
    base = os.path.splitext(path)[0]
    folder = os.path.dirname(path) or "."
    for target in (path, base + ".light.json"):
        if os.path.isdir(target):
            raise InputError(f"{target}: is a folder")
    if os.path.exists(base + "_meshes") and not os.path.isdir(base + "_meshes"):
        raise InputError(f"{base}_meshes: is not a folder")
    if not os.path.isdir(folder):
        raise InputError(f"{path}: no such folder {folder}")
    try:
        staging = tempfile.mkdtemp(dir=folder, prefix="." + os.path.basename(base) + ".tmp-")
    except OSError as e:
        raise InputError(f"{path}: cannot write there: {e.strerror}") from None
    try:
        command, warnings = _export_into(staging, path, scene)
        _move_into_place(staging, path)
    except InputError as e:
        raise InputError(f"{path}: scene '{scene.name}' not exported: {e}") from None
    except OSError as e:
        raise InputError(f"{path}: cannot write the export: {e.strerror}") from None
    finally:
        shutil.rmtree(staging, ignore_errors=True)
    return command, warnings


def _export_into(staging, path, scene):
    """Writes the export of `path` into the folder `staging`, under the names it will have."""
    depsgraph = bpy.context.evaluated_depsgraph_get()
    warnings = []
    base = os.path.splitext(path)[0]
    mesh_folder = os.path.basename(base) + "_meshes"
    os.makedirs(os.path.join(staging, mesh_folder))
    lights, objects = [], []
    for obj in sorted(scene.objects, key=lambda o: o.name):
        if obj.hide_render:
            continue
        if obj.type == "LIGHT":
            if obj.data.type == "AREA":
                lights.append(light_json(obj, warnings))
            else:
                warnings.append(f"light '{obj.name}': a {obj.data.type.lower()} light is not exported "
                                "(aaf renders area lights)")
        elif obj.type == "MESH":
            file_name = f"{len(objects) + 1:03d}_{bpy.path.clean_name(obj.name)}.obj"
            if _write_obj(obj, depsgraph, os.path.join(staging, mesh_folder, file_name)) == 0:
                continue
            objects.append({"type": "obj", "file": mesh_folder + "/" + file_name,
                            "id": obj.pass_index if obj.pass_index > 0 else len(objects) + 1,
                            "material": {"albedo": _albedo(obj)}})
        elif obj.type not in ("CAMERA", "EMPTY"):
            warnings.append(f"object '{obj.name}': a {obj.type.lower()} is not exported")
    if not lights:
        raise InputError("the scene has no area light (aaf renders area lights)")
    if not objects:
        raise InputError("the scene has no mesh")
    document = {"format_version": 1, "name": bpy.path.clean_name(scene.name),
                "camera": camera_json(scene, warnings), "lights": lights, "objects": objects}
    with open(os.path.join(staging, os.path.basename(path)), "w") as out:
        json.dump(document, out, indent=2)
    with open(os.path.join(staging, os.path.basename(base) + ".light.json"), "w") as out:
        json.dump(lights[0], out, indent=2)
    width, height = image_size(scene)
    command = f"aaf render {path} --width {width} --height {height} --aovs all -o {base}.aovs.exr"
    return command, warnings


def _move_into_place(staging, path):
    """Renames the staged export over `path`'s: the meshes folder first (an
    older one is moved into the staging folder, which is then removed), the
    scene last, so a scene file always names meshes that exist."""
    base = os.path.splitext(path)[0]
    mesh_dir = base + "_meshes"
    if os.path.isdir(mesh_dir):
        os.replace(mesh_dir, os.path.join(staging, "previous_meshes"))
    os.replace(os.path.join(staging, os.path.basename(mesh_dir)), mesh_dir)
    os.replace(os.path.join(staging, os.path.basename(base) + ".light.json"), base + ".light.json")
    os.replace(os.path.join(staging, os.path.basename(path)), path)


class _quiet_stderr:
    """Sends file descriptor 2 to /dev/null while the block runs."""

    def __enter__(self):
        sys.stderr.flush()
        self.saved = os.dup(2)
        null = os.open(os.devnull, os.O_WRONLY)
        os.dup2(null, 2)
        os.close(null)

    def __exit__(self, *exc):
        os.dup2(self.saved, 2)
        os.close(self.saved)
        return False


def load_into_compositor(path, scene=None):
    """Opens aaf's output `path` in an Image node of the compositor and sends
    its Combined pass to the Composite node; returns the node's pass names."""
    scene = scene or bpy.context.scene
    if not os.path.isfile(path):
        raise InputError(f"{path}: no such file")
    # Blender's image readers print their own complaints on stderr; the
    # failure is reported once, below, naming the file.
    with _quiet_stderr():
        try:
            image = bpy.data.images.load(path, check_existing=True)
        except RuntimeError as e:
            raise InputError(f"{path}: Blender cannot read it ({' '.join(str(e).split())})") from None
        readable = image.has_data or (image.size[0] > 0 and image.size[1] > 0)
    if not readable:
        bpy.data.images.remove(image)
        raise InputError(f"{path}: Blender cannot read it as an image")
    scene.use_nodes = True
    tree = scene.node_tree
    source = tree.nodes.new("CompositorNodeImage")
    source.image = image
    source.label = "aaf: " + os.path.basename(path)
    composite = next((n for n in tree.nodes if n.type == "COMPOSITE"), None) or \
        tree.nodes.new("CompositorNodeComposite")
    if "Combined" in source.outputs:
        tree.links.new(source.outputs["Combined"], composite.inputs["Image"])
    return [socket.name for socket in source.outputs]


class AAF_OT_export(bpy.types.Operator):
    """Export the scene for aaf render (meshes, camera, area lights)"""
    bl_idname = "aaf.export_scene"
    bl_label = "aaf scene (.json)"
    filepath: bpy.props.StringProperty(subtype="FILE_PATH")

    def execute(self, context):
        try:
            command, warnings = export_scene(self.filepath, context.scene)
        except InputError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        for warning in warnings:
            self.report({"WARNING"}, warning)
        self.report({"INFO"}, command)
        return {"FINISHED"}

    def invoke(self, context, event):
        self.filepath = bpy.path.ensure_ext(bpy.data.filepath or "scene", ".json")
        context.window_manager.fileselect_add(self)
        return {"RUNNING_MODAL"}


class AAF_OT_load(bpy.types.Operator):
    """Load an aaf output (filtered EXR) into the compositor"""
    bl_idname = "aaf.load_outputs"
    bl_label = "aaf: load outputs into the compositor"
    filepath: bpy.props.StringProperty(subtype="FILE_PATH")

    def execute(self, context):
        try:
            load_into_compositor(self.filepath, context.scene)
        except InputError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        return {"FINISHED"}

    def invoke(self, context, event):
        context.window_manager.fileselect_add(self)
        return {"RUNNING_MODAL"}


def _menu_export(self, context):
    self.layout.operator(AAF_OT_export.bl_idname, text="aaf scene (.json)")


def register():
    bpy.utils.register_class(AAF_OT_export)
    bpy.utils.register_class(AAF_OT_load)
    bpy.types.TOPBAR_MT_file_export.append(_menu_export)


def unregister():
    bpy.types.TOPBAR_MT_file_export.remove(_menu_export)
    bpy.utils.unregister_class(AAF_OT_load)
    bpy.utils.unregister_class(AAF_OT_export)


USAGE = "usage: blender -b FILE --python aaf_bridge.py -- export OUT.json | load FILTERED.exr"


def _main(args):
    if len(args) == 2 and args[0] == "export":
        command, warnings = export_scene(args[1])
        for warning in warnings:
            print("aaf-bridge: warning:", warning)
        print("aaf-bridge: wrote", args[1], "; render with:", command)
    elif len(args) == 2 and args[0] == "load":
        print("aaf-bridge: passes", load_into_compositor(args[1]))
    else:
        raise UsageError(f"expected export OUT.json or load FILTERED.exr, got {' '.join(args) or 'nothing'}; "
                         + USAGE)


def _run(args):
    """_main with aaf's exit codes: Blender itself exits 0 after a script's
    exception, so every failure is caught here and made one line and a code."""
    try:
        _main(args)
    except UsageError as e:
        code, message = 2, str(e)
    except InputError as e:
        code, message = 3, str(e)
    except Exception as e:  # a bug, not a bad input: still one line and a failing exit code
        code, message = 1, f"{type(e).__name__}: {e}"
    else:
        return
    print("aaf-bridge: error: " + " ".join(message.split()), file=sys.stderr)
    sys.stdout.flush()
    sys.exit(code)


if __name__ == "__main__" and "--" in sys.argv:
    _run(sys.argv[sys.argv.index("--") + 1:])
