#include <functional>
#include <map>

#include "aaf/core/error.h"
#include "aaf/trace/render.h"
#include "scene_description.h"

namespace aaf::trace {

namespace {

using SceneFactory = std::function<SceneDescription(int, int)>;

const std::map<std::string, SceneFactory> &scene_factories() {
    static const std::map<std::string, SceneFactory> factories = {
        {"bench", make_bench_scene},
        {"grids", make_grids_scene},
        {"spheres", make_spheres_scene},
        {"tentacles", make_tentacles_scene},
    };
    return factories;
}

}  // namespace

std::vector<std::string> builtin_scene_names() {
    std::vector<std::string> names;
    for (const auto &entry : scene_factories()) names.push_back(entry.first);
    return names;
}

SceneDescription make_builtin_scene(const std::string &name, int width, int height) {
    const auto &factories = scene_factories();
    auto it = factories.find(name);
    if (it == factories.end()) {
        std::string known;
        for (const auto &entry : factories) known += (known.empty() ? "" : ", ") + entry.first;
        throw Error("unknown scene '" + name + "' (built-in scenes: " + known + ")");
    }
    return it->second(width, height);
}

}  // namespace aaf::trace
