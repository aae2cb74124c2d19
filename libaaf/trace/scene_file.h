#pragma once

#include <string>
#include <vector>

#include "scene_description.h"

namespace aaf::trace {

/// Reads a JSON scene file (the format of libaaf/SCENE_FORMAT.md): camera,
/// materials, area lights, objects (primitives and Wavefront OBJ meshes, paths
/// relative to the file) and keyframes. The camera renders `width` x `height`.
/// Every value is range-checked before it can reach Embree (SCENE_FORMAT.md,
/// "Limits": coordinates, lengths, aperture, intensities, colours).
/// Throws aaf::InputError "<file>: <JSON path>: <problem>", or
/// "<file>: invalid JSON at line L, column C: <problem>" for malformed JSON
/// ("<file>: invalid JSON: <problem>" where the parser gives no position, as
/// for a number beyond double's range); every message is one line.
SceneDescription load_scene_file(const std::string &path, int width, int height);

/// The files loading the scene file `path` reads: `path` itself, then the
/// file of every `obj` object (relative to the scene's folder), in the order
/// written. Reads only the JSON (a malformed one throws as load_scene_file()
/// does), and not even that from a pipe, which only the loader may read (the
/// list is then `path` alone); an entry may name a file that does not exist.
std::vector<std::string> scene_file_inputs(const std::string &path);

/// Directories searched for scenes given by name, in order: each entry of
/// $AAF_SCENE_PATH (':'-separated), then `../share/aaf/scenes` beside the
/// running program (an installed tree, wherever it was moved), then the
/// install prefix's and the source tree's `testdata/scenes`.
std::vector<std::string> scene_directories();

/// The file of a scene given as a path (anything ending in .json or holding a
/// '/') or as a name looked up as NAME.json in scene_directories(). Throws
/// aaf::InputError listing the known names when there is none.
std::string resolve_scene(const std::string &name_or_path);

}  // namespace aaf::trace
