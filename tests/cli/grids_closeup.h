#pragma once

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

namespace aaf_test {

/// grids seen through a 7 degree lens aimed at its penumbrae: at 96x72 its
/// pixels cover ~1 cm of ground, as the full view's do at 640x480, so small
/// images still give AAF's world-space beta (Eq. 13) several pixels to work
/// with. Written under `dir`; returns the scene file's path.
inline std::string write_grids_closeup(const std::filesystem::path &dir) {
    nlohmann::json scene = nlohmann::json::parse(std::ifstream(std::string(AAF_SCENE_DIR) + "/grids.json"));
    scene["name"] = "grids_closeup";
    scene["camera"]["fov_y_deg"] = 7.0;
    scene["camera"]["look_at"] = {0.6, 0.0, 0.9};
    const std::string path = (dir / "grids_closeup.json").string();
    std::ofstream(path) << scene.dump(1);
    return path;
}

}  // namespace aaf_test
