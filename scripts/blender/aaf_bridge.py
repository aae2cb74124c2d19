"""aaf bridge for Blender 3.4: export the active scene to aaf's JSON scene
format (libaaf/SCENE_FORMAT.md) so that `aaf render` produces every AOV for
the same shot, and read aaf's outputs back into the compositor.

As an add-on (Edit > Preferences > Add-ons > Install, this file; its
preferences hold the path to the `aaf` executable, empty for the one on
PATH): the panel Properties > Render > aaf exports the shot, renders it with
`aaf render --aovs METHOD`, filters it with `aaf filter METHOD` (the methods
`aaf filter --help` lists) and loads the result into the compositor, one
button per step and one for all four. `aaf` runs in the background with a
progress bar; Esc stops it, and nothing it was writing is left behind. The
same steps are the operators aaf.export_shot, aaf.render, aaf.filter,
aaf.load_result and aaf.run_all; from a script in `blender -b`, a failed
step prints one line `aaf-bridge: error: ...` and Blender exits with aaf's
exit code. File > Export > "aaf scene (.json)" and the operator "aaf: load
outputs into the compositor" (F3 search) export or load one file.

Headless (Debian's blender, scripts/install_blender.sh):

  blender -b shot.blend --python scripts/blender/aaf_bridge.py -- export OUT.json
  blender -b shot.blend --python scripts/blender/aaf_bridge.py -- load FILTERED.exr

`export` writes OUT.json (meshes as OBJ files under OUT_meshes/, written by
Blender's OBJ exporter with their world transforms applied; the camera with
its depth of field; every area light, the first one the key light),
OUT.light.json (the key light alone, for `aaf filter --light` on a Cycles
render of the same shot; OUT is the path less .json) and prints the `aaf
render` command with the scene's resolution; everything is written into a
temporary folder beside OUT.json first and renamed into place, so a failed
export leaves nothing behind. `load` puts the file in an Image node of the
compositor, its Combined pass into the Composite node.

A failure is one line `aaf-bridge: error: ...` on stderr and aaf's exit code:
2 usage, 3 a scene that cannot be exported, a file that cannot be read or
written or an `aaf` that cannot be run, 1 anything else.

What is exported and what is not (libaaf/RENDERERS.md "Blender"): mesh objects
(evaluated as Cycles renders them: modifiers at their render settings,
triangulated as Cycles does), their material's Principled BSDF base colour
as albedo (0.75 without one); perspective cameras (sensor fit and shift-free
framing; Blender's shift is not exported); area lights (square, rectangle; a
disk or an ellipse as the rectangle around it, with a warning), emitting
uniformly, intensity = power / pi W/sr. Point, spot and sun lights, curves,
volumes and textures are skipped with a warning.
"""
import glob
import json
import math
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
import threading
import time

import bpy
import mathutils

bl_info = {
    "name": "aaf bridge",
    "author": "libaaf",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "Properties > Render > aaf; File > Export > aaf scene (.json)",
    "description": "Export the shot, render and filter it with aaf, load the result into the compositor",
    "category": "Render",
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


def _write_obj(obj, path):
    """Writes the mesh of `obj` as Cycles renders it (modifiers at their render
    settings) in world coordinates, triangulated as Cycles triangulates it
    (quads split along their first diagonal, n-gons by ear clipping; Blender's
    OBJ exporter would split quads along their shorter one), with Blender's
    OBJ exporter; returns the number of triangles. The exporter sees a
    temporary scene holding the object alone, so the user's selection and
    viewport visibility neither matter nor change."""
    active = obj.modifiers.active
    triangulate = obj.modifiers.new("aaf export triangulation", "TRIANGULATE")
    triangulate.quad_method, triangulate.ngon_method, triangulate.min_vertices = "FIXED", "CLIP", 4
    alone = bpy.data.scenes.new("aaf export")
    try:
        alone.collection.objects.link(obj)
        # The exporter prints each file it writes on stderr, which is for errors here.
        with bpy.context.temp_override(scene=alone, view_layer=alone.view_layers[0]), _quiet_stderr():
            # forward Y, up Z: Blender's own axes, as the camera and lights are written.
            bpy.ops.wm.obj_export(filepath=path, export_eval_mode="DAG_EVAL_RENDER", apply_modifiers=True,
                                  forward_axis="Y", up_axis="Z", global_scale=1.0, export_uv=False,
                                  export_normals=False, export_materials=False, export_triangulated_mesh=False)
    finally:
        bpy.data.scenes.remove(alone)
        obj.modifiers.remove(triangulate)
        obj.modifiers.active = active
    with open(path) as written:
        return sum(1 for line in written if line.startswith("f "))


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
            if _write_obj(obj, os.path.join(staging, mesh_folder, file_name)) == 0:
                os.remove(os.path.join(staging, mesh_folder, file_name))
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
    its Combined pass to the Composite node; returns the node's pass names.
    Loading a file again re-reads it into the node that already shows it."""
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
        image.reload()  # an image loaded before holds the file's earlier pixels and layers
        has_pixels = image.has_data or (image.size[0] > 0 and image.size[1] > 0)
        # A multilayer EXR has neither pixels nor a size until the compositor
        # asks for its layers; asking for them above read its header.
        readable = has_pixels or image.type == "MULTILAYER"
    if not readable:
        bpy.data.images.remove(image)
        raise InputError(f"{path}: Blender cannot read it as an image")
    scene.use_nodes = True
    tree = scene.node_tree
    source = next((n for n in tree.nodes if n.type == "IMAGE" and n.image == image), None) or \
        tree.nodes.new("CompositorNodeImage")
    source.image = image  # also rebuilds the node's pass sockets from the file's layers
    source.label = "aaf: " + os.path.basename(path)
    composite = next((n for n in tree.nodes if n.type == "COMPOSITE"), None) or \
        tree.nodes.new("CompositorNodeComposite")
    if "Combined" in source.outputs:
        tree.links.new(source.outputs["Combined"], composite.inputs["Image"])
    return [socket.name for socket in source.outputs]


class StepError(RuntimeError):
    """A step of the add-on's pipeline that failed, with aaf's exit code for it."""

    def __init__(self, code, message):
        super().__init__(message)
        self.code = code


def find_aaf(path=None):
    """The `aaf` executable: `path`, else the add-on's preference, else the one on PATH."""
    if path is None:
        addon = bpy.context.preferences.addons.get(__name__)
        path = addon.preferences.aaf_path if addon is not None and addon.preferences is not None else ""
    if not path:
        found = shutil.which("aaf")
        if found is None:
            raise StepError(3, "aaf is not on PATH; set the aaf executable in the add-on's preferences "
                               "(Edit > Preferences > Add-ons > aaf bridge)")
        return found
    path = os.path.abspath(bpy.path.abspath(path))
    if not os.path.isfile(path) or not os.access(path, os.X_OK):
        raise StepError(3, f"{path}: the aaf executable set in the add-on's preferences is not an "
                           "executable file")
    return path


def filter_methods(aaf):
    """[(name, description)] of the methods `aaf filter --help` lists (its Subcommands section)."""
    done = subprocess.run([aaf, "filter", "--help"], stdin=subprocess.DEVNULL, capture_output=True,
                          text=True, timeout=30)
    if done.returncode != 0:
        raise StepError(done.returncode, f"{aaf} filter --help exited {done.returncode}")
    lines = done.stdout.splitlines()
    start = lines.index("Subcommands:") + 1 if "Subcommands:" in lines else len(lines)
    methods = []
    for line in lines[start:]:
        match = re.match(r"^  (\S+)\s+(.*)$", line)
        if not match:
            break
        methods.append((match.group(1), match.group(2).strip()))
    return methods


_RENDER_PROGRESS = re.compile(r"^render: (\d+)/(\d+) spp")
_CANCEL_GRACE_S = 2.0  # a render stops after its current round; past this it is killed


class AafJob:
    """One `aaf` run that writes `output`. aaf writes into a hidden file
    beside it, renamed over `output` when aaf succeeds and removed, with
    any temporary of aaf's, when aaf fails or is cancelled: `output` is
    never half-written (an interrupted render would leave a checkpoint)."""

    def __init__(self, step, make_argv, output):
        self.step, self.output, self.progress, self.lines = step, output, 0.0, []
        folder = os.path.dirname(output) or "."
        try:
            handle, self.staging = tempfile.mkstemp(dir=folder, prefix="." + os.path.basename(output) + ".",
                                                    suffix=".partial.exr")
        except OSError as e:
            raise StepError(3, f"{output}: cannot write there: {e.strerror}") from None
        os.close(handle)
        argv = make_argv(self.staging)
        try:
            self.process = subprocess.Popen(argv, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                            stderr=subprocess.PIPE, text=True)
        except OSError as e:
            self._discard()
            raise StepError(3, f"{argv[0]}: cannot run aaf: {e.strerror}") from None
        self.reader = threading.Thread(target=self._read, daemon=True)
        self.reader.start()

    def _read(self):
        for line in self.process.stderr:
            match = _RENDER_PROGRESS.match(line)
            if match:
                self.progress = int(match.group(1)) / max(1, int(match.group(2)))
            elif line.strip():
                self.lines = self.lines[-19:] + [line.strip()]

    def poll(self):
        """False while aaf runs; True once `output` is in place. Raises StepError when aaf failed."""
        code = self.process.poll()
        if code is None:
            return False
        self.reader.join()
        if code != 0:
            self._discard()
            errors = [line for line in self.lines if line.startswith("aaf: error: ")]
            detail = errors[-1][len("aaf: error: "):] if errors else \
                (self.lines[-1] if self.lines else f"exited with code {code}")
            if code < 0:
                detail = f"killed by signal {-code}"
            raise StepError(code if code > 0 else 1, f"aaf {self.step}: {' '.join(detail.split())}")
        try:
            os.replace(self.staging, self.output)
        except OSError as e:
            self._discard()
            raise StepError(3, f"{self.output}: cannot write it: {e.strerror}") from None
        self.progress = 1.0
        return True

    def cancel(self):
        """Stops aaf (SIGTERM, then SIGKILL) and removes what it wrote; `output` stays as it was."""
        if self.process.poll() is None:
            self.process.terminate()
            try:
                self.process.wait(timeout=_CANCEL_GRACE_S)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
        self.reader.join()
        self._discard()

    def _discard(self):
        folder = os.path.dirname(self.staging)
        aaf_temporaries = glob.glob(os.path.join(glob.escape(folder),
                                                 "." + glob.escape(os.path.basename(self.staging)) + ".tmp-*"))
        for path in [self.staging] + aaf_temporaries:
            try:
                os.remove(path)
            except FileNotFoundError:
                pass


def shot_paths(scene):
    """The shot's files: (scene JSON, aaf's render of it, the filtered render), from the scene's aaf settings."""
    if scene.aaf.shot_path.startswith("//") and not bpy.data.filepath:
        raise StepError(3, f"shot path {scene.aaf.shot_path} is relative to the .blend file, which is not saved: "
                           "save it, or give the shot an absolute path")
    path = bpy.path.ensure_ext(os.path.abspath(bpy.path.abspath(scene.aaf.shot_path)), ".json")
    base = os.path.splitext(path)[0]
    return path, base + ".aovs.exr", base + ".filtered.exr"


class Pipeline:
    """Steps ("export", "render", "filter", "load") run in order on a scene.
    tick() advances without blocking (the modal operator calls it on a timer;
    `aaf` runs as a subprocess), run() goes to the end; cancel() stops it.
    Both raise StepError for a failed step; `reports` collects what each
    step has to say, as (level, text)."""

    def __init__(self, scene, steps):
        self.scene, self.steps, self.pending, self.job, self.reports = scene, tuple(steps), list(steps), None, []
        self.aaf = find_aaf() if {"render", "filter"} & set(steps) else None
        self.method = scene.aaf.method

    @property
    def progress(self):
        """0 to 1 over every step."""
        done = len(self.steps) - len(self.pending) - (1 if self.job else 0)
        return (done + (self.job.progress if self.job else 0.0)) / len(self.steps)

    @property
    def status(self):
        return f"aaf {self.job.step}" if self.job else "aaf"

    def tick(self):
        """Runs the steps that do not wait on aaf; True once every step is done."""
        while True:
            if self.job is not None:
                if not self.job.poll():
                    return False
                self.reports.append(("INFO", f"aaf {self.job.step}: wrote {self.job.output}"))
                self.job = None
            if not self.pending:
                return True
            self.job = getattr(self, "_" + self.pending.pop(0))()

    def run(self, on_progress=None):
        try:
            while not self.tick():
                if on_progress:
                    on_progress(self)
                time.sleep(0.05)
        except KeyboardInterrupt:
            self.cancel()
            raise

    def cancel(self):
        if self.job is not None:
            self.job.cancel()
            self.job = None
        self.pending = []

    def _export(self):
        path = shot_paths(self.scene)[0]
        for obj in bpy.context.objects_in_mode:
            obj.update_from_editmode()  # an edit in progress is part of the shot
        try:
            os.makedirs(os.path.dirname(path), exist_ok=True)
            command, warnings = export_scene(path, self.scene)
        except (InputError, OSError) as e:
            raise StepError(3, str(e)) from None
        self.reports += [("WARNING", warning) for warning in warnings] + [("INFO", f"exported {path}")]

    def _render(self):
        path, aovs, _ = shot_paths(self.scene)
        width, height = image_size(self.scene)
        return AafJob("render", lambda out: [
            self.aaf, "render", path, "--width", str(width), "--height", str(height),
            "--spp", str(self.scene.aaf.spp), "--aovs", self.method, "--progress", "lines", "-o", out], aovs)

    def _filter(self):
        _, aovs, filtered = shot_paths(self.scene)
        try:
            options = shlex.split(self.scene.aaf.filter_options)
        except ValueError as e:
            raise StepError(2, f"filter options '{self.scene.aaf.filter_options}': {e}") from None
        return AafJob("filter", lambda out: [
            self.aaf, "filter", self.method, aovs, "-o", out, "--progress", "none", *options], filtered)

    def _load(self):
        filtered = shot_paths(self.scene)[2]
        try:
            passes = load_into_compositor(filtered, self.scene)
        except InputError as e:
            raise StepError(3, str(e)) from None
        self.reports.append(("INFO", f"compositor: {os.path.basename(filtered)}, passes {', '.join(passes)}"))


_running = None  # the Pipeline a modal operator runs; one at a time
_method_cache = {}  # aaf executable -> enum items; Blender needs the strings kept alive


def _method_items(self, context):
    try:
        aaf = find_aaf()
    except StepError:
        aaf = None
    if aaf not in _method_cache:
        try:
            methods = filter_methods(aaf) if aaf else []
        except (OSError, subprocess.SubprocessError, StepError):
            methods = []
        _method_cache[aaf] = [(name, name, help) for name, help in methods] or \
            [("aaf", "aaf", "Set the aaf executable in the add-on's preferences to list every method")]
    return _method_cache[aaf]


class AafShotSettings(bpy.types.PropertyGroup):
    shot_path: bpy.props.StringProperty(
        name="Shot", subtype="FILE_PATH", default="//aaf/shot.json",
        description="The exported scene (aaf's JSON); aaf's render and the filtered render are written "
                    "beside it as .aovs.exr and .filtered.exr")
    method: bpy.props.EnumProperty(
        name="Method", items=_method_items,
        description="aaf filter METHOD; the render writes the AOVs it reads (aaf render --aovs METHOD)")
    spp: bpy.props.IntProperty(name="Samples", default=16, min=1, soft_max=1024,
                               description="Light samples per pixel of aaf render (--spp)")
    filter_options: bpy.props.StringProperty(
        name="Filter options", default="",
        description="More options of aaf filter METHOD, as on its command line (aaf filter METHOD --help)")


class AafPreferences(bpy.types.AddonPreferences):
    bl_idname = __name__

    aaf_path: bpy.props.StringProperty(
        name="aaf executable", subtype="FILE_PATH", default="",
        description="The aaf command line tool; empty: the aaf found on PATH")

    def draw(self, context):
        self.layout.prop(self, "aaf_path")
        try:
            self.layout.label(text="Runs " + find_aaf(self.aaf_path), icon="CHECKMARK")
        except StepError as e:
            self.layout.label(text=str(e), icon="ERROR")


class _PipelineOperator:
    """Runs `steps`: blocking from a script (execute), as a modal operator
    with a progress bar from the interface (invoke), where Esc cancels.
    A failure is reported as one line; headless, Blender then exits with
    aaf's exit code for it."""
    steps = ()

    @classmethod
    def poll(cls, context):
        return _running is None

    def execute(self, context):
        try:
            pipeline = Pipeline(context.scene, self.steps)
            wm = context.window_manager
            wm.progress_begin(0, 100)
            try:
                pipeline.run(lambda p: wm.progress_update(100.0 * p.progress))
            finally:
                wm.progress_end()
        except StepError as e:
            return self._fail(e)
        self._report(pipeline)
        return {"FINISHED"}

    def invoke(self, context, event):
        global _running
        try:
            self.pipeline = Pipeline(context.scene, self.steps)
            if self.pipeline.tick():
                self._report(self.pipeline)
                return {"FINISHED"}
        except StepError as e:
            return self._fail(e)
        wm = context.window_manager
        self.timer = wm.event_timer_add(0.1, window=context.window)
        wm.modal_handler_add(self)
        wm.progress_begin(0, 100)
        _running = self.pipeline
        self._show(context)
        return {"RUNNING_MODAL"}

    def modal(self, context, event):
        if event.type == "ESC" and event.value == "PRESS":
            step = self.pipeline.status
            self.pipeline.cancel()
            self._end(context)
            self.report({"WARNING"}, f"{step} cancelled; its output was not written")
            return {"CANCELLED"}
        if event.type != "TIMER":
            return {"PASS_THROUGH"}
        try:
            done = self.pipeline.tick()
        except StepError as e:
            self._end(context)
            return self._fail(e)
        if done:
            self._end(context)
            self._report(self.pipeline)
            return {"FINISHED"}
        self._show(context)
        return {"RUNNING_MODAL"}

    def _show(self, context):
        percent = 100.0 * self.pipeline.progress
        context.window_manager.progress_update(percent)
        context.window_manager.aaf_progress = percent
        context.workspace.status_text_set(f"{self.pipeline.status}: {percent:.0f} %  (Esc cancels)")
        _redraw_properties(context)

    def _end(self, context):
        global _running
        wm = context.window_manager
        wm.event_timer_remove(self.timer)
        wm.progress_end()
        context.workspace.status_text_set(None)
        _running = None
        _redraw_properties(context)

    def _report(self, pipeline):
        for level, text in pipeline.reports:
            self.report({level}, text)

    def _fail(self, error):
        message = " ".join(str(error).split())
        self.report({"ERROR"}, message)
        if bpy.app.background:  # a script's failure must reach the shell: aaf's exit code
            print("aaf-bridge: error: " + message, file=sys.stderr)
            sys.stdout.flush()
            sys.exit(error.code)
        return {"CANCELLED"}


def _redraw_properties(context):
    for area in context.screen.areas if context.screen else ():
        if area.type == "PROPERTIES":
            area.tag_redraw()


class AAF_OT_export_shot(_PipelineOperator, bpy.types.Operator):
    """Export the scene, camera and area lights in aaf's scene format to the shot path"""
    bl_idname = "aaf.export_shot"
    bl_label = "Export"
    steps = ("export",)


class AAF_OT_render(_PipelineOperator, bpy.types.Operator):
    """Render the exported shot with aaf render, with the AOVs the method reads"""
    bl_idname = "aaf.render"
    bl_label = "Render"
    steps = ("render",)


class AAF_OT_filter(_PipelineOperator, bpy.types.Operator):
    """Filter aaf's render with aaf filter METHOD"""
    bl_idname = "aaf.filter"
    bl_label = "Filter"
    steps = ("filter",)


class AAF_OT_load_result(_PipelineOperator, bpy.types.Operator):
    """Load the filtered render into the compositor, its Combined pass into the Composite node"""
    bl_idname = "aaf.load_result"
    bl_label = "Load"
    steps = ("load",)


class AAF_OT_run_all(_PipelineOperator, bpy.types.Operator):
    """Export the shot, render it with aaf, filter it and load the result into the compositor"""
    bl_idname = "aaf.run_all"
    bl_label = "Export, Render, Filter, Load"
    steps = ("export", "render", "filter", "load")


class RENDER_PT_aaf(bpy.types.Panel):
    bl_label = "aaf"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "render"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        settings = context.scene.aaf
        layout.prop(settings, "shot_path")
        layout.prop(settings, "method")
        layout.prop(settings, "spp")
        layout.prop(settings, "filter_options")
        if _running is not None:
            layout.prop(context.window_manager, "aaf_progress", text=_running.status, slider=True)
            layout.label(text="Esc cancels", icon="CANCEL")
        row = layout.row(align=True)
        for operator in (AAF_OT_export_shot, AAF_OT_render, AAF_OT_filter, AAF_OT_load_result):
            row.operator(operator.bl_idname, text=operator.bl_label)
        layout.operator(AAF_OT_run_all.bl_idname, text=AAF_OT_run_all.bl_label, icon="RENDER_STILL")


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


@bpy.app.handlers.persistent
def _cancel_on_load(*args):
    """Opening another file ends a modal operator without telling it: its aaf is stopped here."""
    global _running
    if _running is not None:
        _running.cancel()
        _running = None


_classes = (AafShotSettings, AafPreferences, AAF_OT_export_shot, AAF_OT_render, AAF_OT_filter,
            AAF_OT_load_result, AAF_OT_run_all, RENDER_PT_aaf, AAF_OT_export, AAF_OT_load)


def register():
    for cls in _classes:
        bpy.utils.register_class(cls)
    bpy.types.Scene.aaf = bpy.props.PointerProperty(type=AafShotSettings)
    bpy.types.WindowManager.aaf_progress = bpy.props.FloatProperty(
        name="Progress", subtype="PERCENTAGE", min=0, max=100, options={"SKIP_SAVE"})
    bpy.types.TOPBAR_MT_file_export.append(_menu_export)
    bpy.app.handlers.load_pre.append(_cancel_on_load)


def unregister():
    _cancel_on_load()
    bpy.app.handlers.load_pre.remove(_cancel_on_load)
    bpy.types.TOPBAR_MT_file_export.remove(_menu_export)
    del bpy.types.WindowManager.aaf_progress
    del bpy.types.Scene.aaf
    for cls in reversed(_classes):
        bpy.utils.unregister_class(cls)


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
