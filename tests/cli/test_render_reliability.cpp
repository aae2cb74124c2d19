#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "run_aaf.h"

// `aaf render` against bad input: outputs that are inputs, scene values that
// would break Embree, option values out of range. Each is refused before
// anything is written, with one `aaf: error:` line and its exit code.

namespace fs = std::filesystem;
using aaf_test::run_aaf;
using aaf_test::scratch_dir;

namespace {

constexpr const char *kSmall = " --width 8 --height 8 --spp 1 --progress none";

std::string bytes_of(const fs::path &path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_file(const fs::path &path, const std::string &text) {
    std::ofstream(path, std::ios::binary) << text;
}

/// Every file under `dir` with its bytes: what a refused run must leave as it was.
std::map<std::string, std::string> snapshot(const fs::path &dir) {
    std::map<std::string, std::string> files;
    for (const auto &entry : fs::recursive_directory_iterator(dir))
        files[entry.path().string()] = entry.is_regular_file() ? bytes_of(entry.path()) : "<dir>";
    return files;
}

/// A scene of a ground plane and an OBJ triangle lit by one light; `objects`
/// replaces the object list.
std::string scene_json(const std::string &objects = R"([{"type": "plane", "size": [4, 4]},
                                                        {"type": "obj", "file": "tri.obj"}])") {
    return R"({"camera": {"position": [0, 2, 4], "look_at": [0, 0, 0]},
  "lights": [{"center": [0, 3, 0], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1], "intensity": 20}],
  "objects": )" +
           objects + "}";
}

const char *const kTriangle = "v 0 0.5 0\nv 1 0.5 0\nv 0 0.5 1\nf 1 2 3\n";

/// Checks that `args` exits `code` with one `aaf: error:` line holding
/// `expected`; returns that line.
std::string check_refused(const std::string &args, int code, const std::string &expected) {
    const auto result = run_aaf(args);
    INFO(args << "\n" << result.output);
    CHECK(result.exit_code == code);
    CHECK_THAT(result.output, Catch::StartsWith("aaf: error: ") && Catch::Contains(expected));
    CHECK(std::count(result.output.begin(), result.output.end(), '\n') == 1);
    return result.output;
}

}  // namespace

TEST_CASE("render refuses an output that is its scene file or an OBJ it loads",
          "[cli][render][reliability]") {
    const fs::path dir = scratch_dir("render_output_is_input");
    write_file(dir / "s.json", scene_json());
    write_file(dir / "tri.obj", kTriangle);
    fs::create_symlink(dir / "s.json", dir / "link.exr");
    const auto before = snapshot(dir);
    const std::string scene = (dir / "s.json").string();
    // The scene itself, under its own name, another path to it, a symlink to it; an OBJ it loads.
    for (const fs::path &output :
         {dir / "s.json", dir / ".." / dir.filename() / "s.json", dir / "link.exr", dir / "tri.obj"}) {
        check_refused("render " + scene + " -o " + output.string() + kSmall, 3,
                      output.string() + ": output would overwrite the input");
        CHECK(snapshot(dir) == before);  // inputs byte-identical, no temporary left
    }
    // A sequence one of whose frames would land on the OBJ: no frame is rendered.
    write_file(dir / "s2.json", scene_json(R"([{"type": "obj", "file": "m.2.obj"}])"));
    write_file(dir / "m.2.obj", kTriangle);
    const auto before_sequence = snapshot(dir);
    check_refused(
        "render " + (dir / "s2.json").string() + " --frames 1-3 -o " + (dir / "m.#.obj").string() + kSmall, 3,
        (dir / "m.2.obj").string() + ": output would overwrite the input");
    CHECK(snapshot(dir) == before_sequence);
    // The same scene to another file renders, also from a pipe (read once, by the loader).
    CHECK(run_aaf("render " + scene + " -o " + (dir / "out.exr").string() + kSmall).exit_code == 0);
    CHECK(fs::exists(dir / "out.exr"));
    const fs::path piped = dir / "pipe.json";
    write_file(piped, scene_json(R"([{"type": "sphere", "radius": 1}])"));
    const std::string through_pipe = "cat " + piped.string() + " | " + AAF_EXECUTABLE;
    CHECK(run_aaf("render /dev/stdin -o " + (dir / "piped.exr").string() + kSmall, through_pipe).exit_code ==
          0);
    CHECK(fs::exists(dir / "piped.exr"));
}

TEST_CASE("render refuses crafted bad scenes: exit 3, one line naming the scene, nothing written",
          "[cli][render][reliability][scene]") {
    const fs::path dir = scratch_dir("render_bad_scenes");
    write_file(dir / "tri.obj", kTriangle);
    write_file(dir / "bad_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
    write_file(dir / "points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    fs::create_directories(dir / "folder.obj");
    const std::string light =
        R"("lights": [{"center": [0, 3, 0], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1]}])";
    const std::string camera = R"("camera": {"position": [0, 2, 4], "look_at": [0, 0, 0]})";
    const std::string sphere = R"("objects": [{"type": "sphere", "radius": 1}])";
    const std::vector<std::pair<std::string, std::string>> scenes = {
        {"{" + camera +
             R"(, "lights": [{"center": [1e20, 3, 0], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1]}], )" +
             sphere + "}",
         "lights[0].center: components must lie in [-1e+06, 1e+06] m"},
        {"{" + camera + R"(, "lights": [{"center": [0, 3, 0], "edge_u": [0, 0, 0], "edge_v": [0, 0, 1]}], )" +
             sphere + "}",
         "lights[0]: edge_u and edge_v must be non-zero"},
        {"{" + camera + R"(, "lights": [{"center": [0, 3, 0], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1],
                                          "intensity": 1e308}], )" +
             sphere + "}",
         "lights[0].intensity: expected a finite number"},
        {"{" + camera + ", " + light + R"(, "objects": [{"type": "sphere", "radius": 1e400}]})",
         "invalid JSON: number overflow parsing '1e400'"},
        {R"({"camera": {"type": "thin_lens", "position": [0, 2, 4], "look_at": [0, 0, 0],
                        "aperture_radius_m": 1e300}, )" +
             light + ", " + sphere + "}",
         "camera.aperture_radius_m: expected a finite number"},
        {R"({"camera": {"type": "thin_lens", "position": [0, 2, 4], "look_at": [0, 0, 0],
                        "aperture_radius_m": -0.1}, )" +
             light + ", " + sphere + "}",
         "camera.aperture_radius_m: must be positive"},
        {"{" + camera + ", " + light + R"(, "objects": [{"type": "obj", "file": "folder.obj"}]})",
         "objects[0].file: cannot open OBJ file"},
        {"{" + camera + ", " + light + R"(, "objects": [{"type": "obj", "file": "missing.obj"}]})",
         "objects[0].file: cannot open OBJ file"},
        {"{" + camera + ", " + light + R"(, "objects": [{"type": "obj", "file": "bad_index.obj"}]})",
         "bad_index.obj"},
        {"{" + camera + ", " + light + R"(, "objects": [{"type": "obj", "file": "points.obj"}]})",
         "points.obj: no triangles"},
        {"{" + camera + ", " + light + R"(, "objects": [{"type": "obj", "file": "tri.obj",
                                                           "transform": {"translate": [0, 0, 999999.9]}}]})",
         "objects[0]: reaches beyond 1e+06 m from the origin"},
    };
    for (std::size_t i = 0; i < scenes.size(); ++i) {
        const fs::path scene = dir / ("scene" + std::to_string(i) + ".json");
        write_file(scene, scenes[i].first);
        const auto before = snapshot(dir);
        const std::string line =
            check_refused("render " + scene.string() + " -o " + (dir / "out.exr").string() + kSmall, 3,
                          scene.string() + ": ");
        CHECK_THAT(line, Catch::Contains(scenes[i].second));
        CHECK(snapshot(dir) == before);
    }
}

TEST_CASE("render option values out of range are usage errors: exit 2, one line, nothing written",
          "[cli][render][reliability][usage]") {
    const fs::path dir = scratch_dir("render_bad_options");
    const std::string scene = std::string(AAF_SCENE_DIR) + "/grids.json";
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"--spp 0", "spp must lie in [1, 1048576]"},
        {"--width 0", "width and height must lie in [1, 16384]"},
        {"--height 0", "width and height must lie in [1, 16384]"},
        {"--width 16385", "width and height must lie in [1, 16384]"},
        {"--aovs bogus", "--aovs: unknown AOV group 'bogus'"},
        {"--adaptive --spp 9 --max-spp 4", "max spp must lie in [spp, 1048576]"},
        {"--adaptive --mu 0", "--mu: method 'aaf': parameter 'mu' must be in > 0, got 0"},
        {"--threads -1", "threads must lie in [0, 1024]"},
        {"--threads 99999", "threads must lie in [0, 1024]"},
        {"--checkpoint -1", "--checkpoint must be positive"},
        {"--checkpoint 0", "--checkpoint must be positive"},
    };
    for (const auto &[option, message] : cases)
        check_refused("render " + scene + " -o " + (dir / "out.exr").string() + " " + option, 2, message);
    check_refused("render " + scene + " --frames 3-1 -o " + (dir / "f.####.exr").string(), 2,
                  "3-1 ends before it starts");
    check_refused("render " + scene + " --frames '' -o " + (dir / "out.exr").string(), 2,
                  "--frames: empty frame range");
    // CLI11 reports its own validation (its message format is run.cpp's).
    CHECK(run_aaf("render " + scene + " -o " + (dir / "out.exr").string() + " --seed -1").exit_code == 2);
    CHECK(fs::is_empty(dir));
}

TEST_CASE("render --frames with a number beyond int is one usage line, not 'stoi'",
          "[cli][render][reliability][frames]") {
    const fs::path dir = scratch_dir("render_many_frames");
    const std::string scene = std::string(AAF_SCENE_DIR) + "/grids.json";
    const std::string output = " -o " + (dir / "f.####.exr").string();
    check_refused("render " + scene + " --frames 1-99999999999" + output, 2, "99999999999 is out of range");
    CHECK(fs::is_empty(dir));
}

TEST_CASE("render with more threads than cores prints no TBB warning",
          "[cli][render][reliability][threads]") {
    const fs::path dir = scratch_dir("render_many_threads");
    const std::string scene = std::string(AAF_SCENE_DIR) + "/grids.json";
    const auto result =
        run_aaf("render " + scene + " -o " + (dir / "out.exr").string() + kSmall + " --threads 1024");
    INFO(result.output);
    CHECK(result.exit_code == 0);
    CHECK(result.output.find("TBB") == std::string::npos);
    CHECK(result.output.empty());
}
