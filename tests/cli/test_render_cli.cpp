#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/io/exr_io.h"
#include "run_aaf.h"

namespace fs = std::filesystem;
using aaf_test::interrupt_at_first_checkpoint;
using aaf_test::run_aaf;
using aaf_test::scratch_dir;

namespace {

std::string bytes_of(const fs::path &path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// A ground, a box above it and a light that moves 1 m along x from frame 1 to 3.
fs::path write_moving_light_scene(const fs::path &dir) {
    const fs::path path = dir / "moving.json";
    std::ofstream(path) << R"({
  "camera": {"position": [0, 4, 4], "look_at": [0, 0, 0]},
  "lights": [{"center": [-0.5, 3, 0], "edge_u": [0.5, 0, 0], "edge_v": [0, 0, 0.5], "intensity": 20}],
  "objects": [{"type": "plane", "size": [10, 10]},
              {"type": "box", "min": [-0.3, 0.8, -0.3], "max": [0.3, 0.9, 0.3], "id": 2}],
  "animation": {"lights": [{"keys": [{"frame": 1, "center": [-0.5, 3, 0]}, {"frame": 3, "center": [0.5, 3, 0]}]}]}
})";
    return path;
}

}  // namespace

TEST_CASE("CLI: render --list shows the shipped scenes", "[cli][render]") {
    const auto result = run_aaf("render --list");
    CHECK(result.exit_code == 0);
    for (const char *name : {"grids", "spheres", "tentacles", "bench", "studio", "gallery", "tilted",
                             "grazing", "contact", "livingroom", "room"})
        CHECK_THAT(result.output, Catch::Contains(std::string(name) + "\n"));
}

TEST_CASE("CLI: a 3-frame sequence with a moving light differs only where the light matters",
          "[cli][render]") {
    const fs::path dir = scratch_dir("render_sequence");
    const fs::path scene = write_moving_light_scene(dir);
    const auto result =
        run_aaf("render " + scene.string() + " --frames 1-3 -o " + (dir / "shot.####.exr").string() +
                " --width 40 --height 30 --spp 16 --aovs all");
    REQUIRE(result.exit_code == 0);
    std::vector<aaf::AovSet> frames;
    for (const char *name : {"shot.0001.exr", "shot.0002.exr", "shot.0003.exr"}) {
        REQUIRE(fs::exists(dir / name));
        frames.push_back(aaf::io::read_aovs((dir / name).string()));
    }
    auto plane = [](const aaf::AovSet &aovs, const std::string &name) {
        return std::vector<float>(aovs.channel(name).data, aovs.channel(name).data + aovs.pixel_count());
    };
    for (int f = 1; f < 3; ++f) {
        INFO("frame " << f + 1);
        // The camera and the geometry stand still...
        for (const char *name : {"P.X", "P.Y", "P.Z", "N.Y", "id.object", "Z", "albedo.R", "pixel.size"})
            CHECK(plane(frames[f], name) == plane(frames[0], name));
        CHECK(plane(frames[f], "motion.X") == std::vector<float>(frames[f].pixel_count(), 0.0f));
        // ...the light and therefore the shadow move.
        CHECK(std::get<aaf::Vec3>(frames[f].attributes.at(aaf::attr::kLightCenter)).x ==
              Approx(-0.5f + 0.5f * float(f)));
        CHECK(plane(frames[f], "shadow.V") != plane(frames[f - 1], "shadow.V"));
        CHECK(plane(frames[f], "unshadowed.R") != plane(frames[f - 1], "unshadowed.R"));
    }
    // Where: the box's shadow on the ground is centred where a ray from the
    // light's centre through the box's centre (height 0.85 m) meets it:
    // x = L + (0 - L) 3 / (3 - 0.85), i.e. 0.20, 0, -0.20 m for L = -0.5, 0, 0.5.
    // It moves against the light, and ground far from the box stays fully lit.
    std::vector<double> centroid_x;
    for (const aaf::AovSet &aovs : frames) {
        const auto v = plane(aovs, "shadow.V"), x = plane(aovs, "P.X"), z = plane(aovs, "P.Z"),
                   id = plane(aovs, "id.object"), normal_y = plane(aovs, "N.Y");
        double weight = 0, sum_x = 0;
        int far_lit = 0, far = 0, box_lit = 0, box = 0;
        for (std::size_t i = 0; i < v.size(); ++i) {
            if (id[i] == 2 && normal_y[i] > 0.5f) {  // the box's top sees the light unblocked
                ++box;
                box_lit += v[i] == 1.0f;
            }
            if (id[i] != 1) continue;
            if (std::hypot(x[i], z[i]) > 1.2) {  // beyond the penumbra of every frame (0.8 m)
                ++far;
                far_lit += v[i] == 1.0f;
            }
            weight += 1.0 - v[i];
            sum_x += (1.0 - v[i]) * x[i];
        }
        CHECK(far > 100);
        CHECK(far_lit == far);
        CHECK(box > 0);
        CHECK(box_lit == box);
        REQUIRE(weight > 5);  // pixels' worth of shadow in view
        centroid_x.push_back(sum_x / weight);
    }
    CHECK(centroid_x[0] == Approx(0.20).margin(0.05));
    CHECK(centroid_x[1] == Approx(0.0).margin(0.05));
    CHECK(centroid_x[2] == Approx(-0.20).margin(0.05));
    CHECK(centroid_x[0] > centroid_x[1]);
    CHECK(centroid_x[1] > centroid_x[2]);
}

TEST_CASE("CLI: render output is byte-identical for 1 and 2 threads", "[cli][render][determinism]") {
    const fs::path dir = scratch_dir("render_threads");
    for (int threads : {1, 2})
        REQUIRE(run_aaf("render studio --width 48 --height 36 --spp 8 --aovs all --threads " +
                        std::to_string(threads) + " -o " +
                        (dir / ("t" + std::to_string(threads) + ".exr")).string())
                    .exit_code == 0);
    const std::string one = bytes_of(dir / "t1.exr"), two = bytes_of(dir / "t2.exr");
    CHECK(!one.empty());
    CHECK(one == two);
}

TEST_CASE("CLI: a reference rendered in two halves with --resume equals one rendered in one go",
          "[cli][render][resume]") {
    const fs::path dir = scratch_dir("render_resume");
    const std::string common = "render grids --width 32 --height 24 ";
    REQUIRE(run_aaf(common + "--spp 2048 -o " + (dir / "whole.exr").string()).exit_code == 0);
    REQUIRE(run_aaf(common + "--spp 1024 -o " + (dir / "halves.exr").string()).exit_code == 0);
    const auto second = run_aaf(common + "--spp 2048 --resume " + (dir / "halves.exr").string() + " -o " +
                                (dir / "halves.exr").string());
    REQUIRE(second.exit_code == 0);
    CHECK(bytes_of(dir / "halves.exr") == bytes_of(dir / "whole.exr"));

    // A partial render of another seed is refused with one line, and nothing is written.
    const auto refused = run_aaf(common + "--spp 3072 --seed 7 --resume " + (dir / "whole.exr").string() +
                                 " -o " + (dir / "other.exr").string());
    CHECK(refused.exit_code == 3);
    CHECK_THAT(refused.output, Catch::Contains("whole.exr: cannot resume: header attribute 'aaf:seed'"));
    CHECK_FALSE(fs::exists(dir / "other.exr"));
}

TEST_CASE("CLI: --resume refuses a partial render of a scene edited since", "[cli][render][resume]") {
    const fs::path dir = scratch_dir("render_resume_edited");
    const fs::path scene = write_moving_light_scene(dir);
    const std::string partial = (dir / "partial.exr").string();
    const std::string common = "render " + scene.string() + " --width 24 --height 18 ";
    REQUIRE(run_aaf(common + "--spp 1024 -o " + partial).exit_code == 0);
    const std::string before = bytes_of(partial);
    // Move the light (and its first key, which holds at frame 1): same name,
    // seed, size, frame and light kind as before.
    std::string text = bytes_of(scene);
    for (std::size_t at; (at = text.find("[-0.5, 3, 0]")) != std::string::npos;)
        text.replace(at, 12, "[-0.4, 3, 0]");
    std::ofstream(scene) << text;
    const auto refused = run_aaf(common + "--spp 2048 --resume " + partial + " -o " + partial);
    CHECK(refused.exit_code == 3);
    CHECK_THAT(refused.output, Catch::Contains("partial.exr: cannot resume: the scene changed"));
    CHECK(std::count(refused.output.begin(), refused.output.end(), '\n') == 1);
    CHECK(bytes_of(partial) == before);
}

TEST_CASE("CLI: --progress chooses how a single render reports its rounds", "[cli][render][progress]") {
    const fs::path dir = scratch_dir("render_progress");
    const std::string common =
        "render grids --width 16 --height 12 --spp 2048 -o " + (dir / "out.exr").string() + " --progress ";
    const auto jsonl = run_aaf(common + "jsonl");
    REQUIRE(jsonl.exit_code == 0);
    CHECK_THAT(jsonl.output, Catch::Contains(R"("event":"round","seconds":)") &&
                                 Catch::Contains(R"("spp":2048,"spp_done":1024})") &&
                                 Catch::Contains(R"("spp":2048,"spp_done":2048})") &&
                                 Catch::Contains(R"("event":"summary")"));
    const auto openjd = run_aaf(common + "openjd");
    REQUIRE(openjd.exit_code == 0);
    CHECK_THAT(openjd.output,
               Catch::Contains("openjd_progress: 50\n") && Catch::Contains("openjd_progress: 100\n"));
    CHECK(run_aaf(common + "none").output.empty());

    // On a terminal (script(1) gives the render one), `lines` still writes lines, `auto` a bar.
    if (std::system("command -v script >/dev/null 2>&1") != 0) return;
    auto on_terminal = [&](const std::string &mode) {
        const fs::path log = dir / ("tty_" + mode + ".txt");
        const std::string command = std::string(AAF_EXECUTABLE) + " " + common + mode;
        std::system(("script -qec '" + command + "' /dev/null >" + log.string() + " 2>&1").c_str());
        return bytes_of(log);
    };
    const std::string lines = on_terminal("lines"), bar = on_terminal("auto");
    CHECK_THAT(lines, Catch::Contains("render: 1024/2048 spp (50%)"));
    CHECK(lines.find("[") == std::string::npos);
    CHECK_THAT(bar, Catch::Contains("\rrender: [##########          ] 1024/2048 spp"));
}

TEST_CASE("CLI: a bad scene file is one error line naming it, exit 3, no output", "[cli][render][errors]") {
    const fs::path dir = scratch_dir("render_bad_scene");
    std::ofstream(dir / "bad.json") << R"({"camera": {"position": [0, 1, 2], "look_at": [0, 0, 0]},
      "lights": [{"center": [0, 3, 0], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1]}],
      "objects": [{"type": "obj", "file": "nowhere.obj"}]})";
    const auto result =
        run_aaf("render " + (dir / "bad.json").string() + " -o " + (dir / "out.exr").string());
    CHECK(result.exit_code == 3);
    CHECK_THAT(result.output, Catch::StartsWith("aaf: error: ") &&
                                  Catch::Contains("bad.json: objects[0].file: cannot open OBJ file"));
    CHECK(std::count(result.output.begin(), result.output.end(), '\n') == 1);
    const std::size_t first = result.output.find("bad.json");
    CHECK(result.output.find("bad.json", first + 1) == std::string::npos);  // named once
    CHECK_FALSE(fs::exists(dir / "out.exr"));
    CHECK(run_aaf("render nosuchscene -o " + (dir / "out.exr").string()).exit_code == 3);
}

TEST_CASE("CLI: Ctrl-C stops a reference after its round, writes it, and --resume finishes it",
          "[cli][render][resume][interrupt]") {
    const fs::path dir = scratch_dir("render_interrupt");
    const std::string out = (dir / "ref.exr").string(), whole = (dir / "whole.exr").string();
    CHECK(interrupt_at_first_checkpoint(
              "render grids --width 48 --height 36 --spp 16384 --checkpoint 0.001 --threads 1 -o " + out, out,
              dir) == 130);
    const aaf::AovSet partial = aaf::io::read_aovs(out);
    const int done = std::get<int>(partial.attributes.at(aaf::attr::kSppDone));
    CHECK(done < 16384);
    CHECK(done % 1024 == 0);

    REQUIRE(
        run_aaf("render grids --width 48 --height 36 --spp 16384 --resume " + out + " -o " + out).exit_code ==
        0);
    REQUIRE(run_aaf("render grids --width 48 --height 36 --spp 16384 -o " + whole).exit_code == 0);
    CHECK(bytes_of(out) == bytes_of(whole));
}
