#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "aaf/core/util/error.h"
#include "scene_file.h"

using namespace aaf;
namespace fs = std::filesystem;

namespace {

fs::path scratch_path(const std::string &name) {
    return fs::path(AAF_TEST_BINARY_DIR) / "scratch" / "scenes" / name;
}

fs::path scratch(const std::string &name) {
    const fs::path dir = scratch_path(name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

std::string write_file(const fs::path &path, const std::string &text) {
    std::ofstream(path) << text;
    return path.string();
}

/// A valid scene with one object; `objects` replaces the object list.
std::string scene_text(const std::string &objects = R"([{"type": "sphere", "radius": 0.5}])",
                       const std::string &extra = "") {
    return R"({
  "camera": {"position": [0, 2, 5], "look_at": [0, 0, 0]},
  "lights": [{"center": [0, 3, 0], "edge_u": [1, 0, 0], "edge_v": [0, 0, 0.5], "intensity": 20}],
  "objects": )" +
           objects + extra + "\n}\n";
}

/// The message load_scene_file throws for `text`.
std::string load_error(const std::string &name, const std::string &text) {
    const fs::path dir = scratch(name);
    const std::string path = write_file(dir / "scene.json", text);
    try {
        trace::load_scene_file(path, 16, 12);
    } catch (const InputError &e) {
        return e.what();
    }
    return "no error";
}

}  // namespace

TEST_CASE("Scene file: camera, light, materials and primitives are read as written", "[trace][scene]") {
    const fs::path dir = scratch("valid");
    const std::string path = write_file(dir / "scene.json", R"({
  "format_version": 1,
  "name": "probe",
  "camera": {"type": "thin_lens", "position": [0, 2, 5], "look_at": [0, 2, 0], "fov_y_deg": 60,
             "aperture_radius_m": 0.1, "focus_distance_m": 4},
  "materials": {"shiny": {"albedo": [0.2, 0.3, 0.4], "specular": 0.04, "roughness": 0.3}},
  "lights": [{"center": [1, 3, 0], "edge_u": [2, 0, 0], "edge_v": [0, 0, 1], "intensity": 20, "color": [1, 0.5, 0.25]},
             {"center": [0, 5, 0], "edge_u": [0, 0, 1], "edge_v": [1, 0, 0], "profile": "uniform", "sigma_m": 0.3}],
  "objects": [
    {"type": "plane", "size": [4, 2], "id": 7, "material": "shiny"},
    {"type": "box", "min": [0, 0, 0], "max": [1, 1, 1], "transform": {"scale": 2, "rotate_deg": [0, 90, 0], "translate": [10, 0, 0]}},
    {"type": "sphere", "radius": 0.5, "segments": 8, "material": {"albedo": 0.1}},
    {"type": "cylinder", "radius": 0.2, "height": 1, "segments": 6}
  ]
})");
    const trace::SceneDescription scene = trace::load_scene_file(path, 64, 48);
    CHECK(scene.name == "probe");
    CHECK(scene.camera.is_thin_lens());
    CHECK(scene.camera.aperture_radius_m == Approx(0.1f));
    CHECK(scene.camera.focus_distance_m == Approx(4.0f));
    CHECK(scene.camera.tan_half_fov_y == Approx(std::tan(30.0 * 3.14159265358979 / 180.0)));
    CHECK(scene.camera.forward.z == Approx(-1.0f));

    REQUIRE(scene.lights.size() == 2);
    const LightPlane &key = scene.key_light();
    CHECK(key.width_m == Approx(2.0f));
    CHECK(key.height_m == Approx(1.0f));
    // Emits towards edge_u x edge_v = x cross z = -y; sigma defaults to half the shorter side.
    CHECK(key.normal.y == Approx(-1.0f));
    CHECK(key.sigma_m == Approx(0.5f));
    CHECK(key.profile == LightProfile::Gaussian);
    CHECK(scene.lights[0].color.y == Approx(0.5f));
    CHECK(scene.lights[1].plane.normal.y == Approx(1.0f));  // z cross x = +y
    CHECK(scene.lights[1].plane.profile == LightProfile::Uniform);
    CHECK(scene.lights[1].plane.sigma_m == Approx(0.3f));

    REQUIRE(scene.meshes.size() == 4);
    CHECK(scene.meshes[0].object_id == 7);
    CHECK(scene.meshes[0].material.specular.x == Approx(0.04f));
    CHECK(scene.meshes[0].material.roughness == Approx(0.3f));
    CHECK(scene.meshes[0].triangle_count() == 2);
    CHECK(scene.meshes[1].object_id == 2);  // default: index + 1
    CHECK(scene.meshes[1].triangle_count() == 12);
    // Box corner (1, 1, 1): scaled to (2, 2, 2), rotated 90 deg about y to (2, 2, -2), moved by +10 in x.
    bool corner_found = false;
    for (Vec3 p : scene.meshes[1].positions)
        corner_found |=
            std::fabs(p.x - 12) < 1e-4f && std::fabs(p.y - 2) < 1e-4f && std::fabs(p.z + 2) < 1e-4f;
    CHECK(corner_found);
    CHECK(scene.meshes[2].material.albedo.z == Approx(0.1f));
    for (Vec3 p : scene.meshes[2].positions) CHECK(length(p) == Approx(0.5f));
    CHECK(scene.meshes[3].triangle_count() == 6 * 4);  // side quads and two caps
}

TEST_CASE("Scene file: OBJ meshes load with their transform, optionally one id per shape",
          "[trace][scene][obj]") {
    const fs::path dir = scratch("obj");
    write_file(dir / "two.obj", R"(# a quad (triangulated) and a triangle
o quad
v 0 0 0
v 1 0 0
v 1 0 1
v 0 0 1
f 1 2 3 4
o tri
v 0 1 0
v 1 1 0
v 0 1 1
f 5 6 7
)");
    const std::string objects =
        R"([{"type": "obj", "file": "two.obj", "id": 3, "transform": {"translate": [0, 2, 0]}},
      {"type": "obj", "file": "two.obj", "id": 10, "id_per_shape": true}])";
    const std::string path = write_file(dir / "scene.json", scene_text(objects));
    const trace::SceneDescription scene = trace::load_scene_file(path, 16, 12);
    REQUIRE(scene.meshes.size() == 3);
    CHECK(scene.meshes[0].object_id == 3);
    CHECK(scene.meshes[0].triangle_count() == 3);
    CHECK(scene.meshes[0].positions.size() == 7);
    for (Vec3 p : scene.meshes[0].positions) CHECK((p.y == 2.0f || p.y == 3.0f));
    CHECK(scene.meshes[1].object_id == 10);
    CHECK(scene.meshes[1].triangle_count() == 2);
    CHECK(scene.meshes[2].object_id == 11);
    CHECK(scene.meshes[2].triangle_count() == 1);
    CHECK(scene.meshes[2].positions[0].y == 1.0f);
}

TEST_CASE("Scene file: keyframes interpolate linearly and hold outside their range",
          "[trace][scene][animation]") {
    const fs::path dir = scratch("animation");
    const std::string path =
        write_file(dir / "scene.json", scene_text(R"([{"type": "sphere", "radius": 0.5}])", R"(,
  "animation": {"lights": [{"light": 0, "keys": [{"frame": 1, "center": [-1, 3, 0]}, {"frame": 3, "center": [1, 3, 0], "intensity": 40}]}],
                "camera": [{"frame": 1}, {"frame": 11, "position": [10, 2, 5]}]})"));
    trace::SceneDescription scene = trace::load_scene_file(path, 16, 12);
    scene.set_frame(2);
    CHECK(scene.key_light().center.x == Approx(0.0f).margin(1e-6));
    CHECK(scene.lights[0].intensity == Approx(30.0f));  // halfway from the static 20 to 40
    CHECK(scene.camera.eye.x == Approx(1.0f));
    scene.set_frame(-5);
    CHECK(scene.key_light().center.x == Approx(-1.0f));
    CHECK(scene.camera.eye.x == Approx(0.0f).margin(1e-6));
    scene.set_frame(100);
    CHECK(scene.key_light().center.x == Approx(1.0f));
    CHECK(scene.camera.eye.x == Approx(10.0f));
}

TEST_CASE("Scene file: errors name the file, the JSON path and the problem", "[trace][scene][errors]") {
    using Catch::Contains;
    CHECK_THAT(load_error("syntax", "{\n  \"camera\": {\n  \"lights\": ]\n}"),
               Contains("scene.json: invalid JSON at line 3"));
    CHECK_THAT(load_error("missing", scene_text(R"([{"type": "sphere"}])")),
               Contains("scene.json: objects[0]: missing required field 'radius'"));
    CHECK_THAT(load_error("unknown_field", scene_text(R"([{"type": "sphere", "radius": 1, "radus": 2}])")),
               Contains("objects[0].radus: unknown field"));
    CHECK_THAT(load_error("type", scene_text(R"([{"type": "sphere", "radius": "big"}])")),
               Contains("objects[0].radius: expected a number"));
    CHECK_THAT(load_error("negative", scene_text(R"([{"type": "sphere", "radius": -1}])")),
               Contains("objects[0].radius: must be positive"));
    CHECK_THAT(load_error("material", scene_text(R"([{"type": "sphere", "radius": 1, "material": "gold"}])")),
               Contains("objects[0].material: unknown material 'gold'"));
    CHECK_THAT(load_error("kind", scene_text(R"([{"type": "torus"}])")),
               Contains("objects[0].type: unknown object type 'torus'"));
    CHECK_THAT(load_error("obj", scene_text(R"([{"type": "obj", "file": "missing.obj"}])")),
               Contains("objects[0].file: cannot open OBJ file"));
    CHECK_THAT(load_error("no_lights", R"({"camera": {"position": [0, 2, 5], "look_at": [0, 0, 0]},
                                          "lights": [], "objects": [{"type": "sphere", "radius": 1}]})"),
               Contains("lights: a scene needs at least one light"));
    CHECK_THAT(load_error("skew_light", R"({"camera": {"position": [0, 2, 5], "look_at": [0, 0, 0]},
        "lights": [{"center": [0, 3, 0], "edge_u": [1, 0, 0], "edge_v": [1, 0, 1]}],
        "objects": [{"type": "sphere", "radius": 1}]})"),
               Contains("lights[0]: edge_u and edge_v must be orthogonal"));
    CHECK_THAT(load_error("keys", scene_text(R"([{"type": "sphere", "radius": 1}])",
                                             R"(, "animation": {"camera": [{"frame": 2}, {"frame": 1}]})")),
               Contains("animation.camera[1].frame: frames must increase"));
    CHECK_THROWS_WITH(trace::load_scene_file((scratch("none") / "nope.json").string(), 8, 8),
                      Contains("nope.json: cannot open scene file"));
    // A folder read as empty JSON; /dev/zero never ended.
    for (const std::string &path : {scratch("folder.json").string(), std::string("/dev/zero")})
        CHECK_THROWS_WITH(trace::load_scene_file(path, 8, 8),
                          path + ": cannot open scene file (a folder or device, not a file)");
}

TEST_CASE("Scene file: animation keys are checked like static values", "[trace][scene][errors]") {
    using Catch::Contains;
    auto animated = [](const std::string &animation) {
        return scene_text(R"([{"type": "sphere", "radius": 1}])", ", \"animation\": " + animation);
    };
    CHECK_THAT(load_error("key_fov_0", animated(R"({"camera": [{"frame": 1, "fov_y_deg": 0}]})")),
               Contains("scene.json: animation.camera[0].fov_y_deg: must lie in [0.001, 180)"));
    CHECK_THAT(
        load_error("key_fov_180", animated(R"({"camera": [{"frame": 1}, {"frame": 2, "fov_y_deg": 180}]})")),
        Contains("scene.json: animation.camera[1].fov_y_deg: must lie in [0.001, 180)"));
    // The static look_at is the origin: a key moving the camera there looks nowhere.
    CHECK_THAT(load_error("key_look_at", animated(R"({"camera": [{"frame": 1, "position": [0, 0, 0]}]})")),
               Contains("scene.json: animation.camera[0]: position and look_at must differ"));
    CHECK_THAT(load_error("key_up", animated(R"({"camera": [{"frame": 1, "position": [0, 5, 0]}]})")),
               Contains("scene.json: animation.camera[0]: up must not be parallel to the view"));
    CHECK_THAT(
        load_error("key_intensity", animated(R"({"lights": [{"keys": [{"frame": 1, "intensity": -1}]}]})")),
        Contains("scene.json: animation.lights[0].keys[0].intensity: must not be negative"));
    // Two tracks for one light, or two camera tracks (JSON would keep only the last).
    CHECK_THAT(load_error("two_tracks", animated(R"({"lights": [{"light": 0, "keys": [{"frame": 1}]},
                                                               {"keys": [{"frame": 2}]}]})")),
               Contains("scene.json: animation.lights[1]: light 0 already has a track"));
    CHECK_THAT(load_error("two_cameras", animated(R"({"camera": [{"frame": 1}], "camera": [{"frame": 2}]})")),
               Contains("scene.json: animation.camera: duplicate key"));
    CHECK_THAT(
        load_error(
            "duplicate_in_array",
            scene_text(R"([{"type": "sphere", "radius": 1}, {"type": "sphere", "radius": 1, "radius": 2}])")),
        Contains("scene.json: objects[1].radius: duplicate key"));
}

TEST_CASE("Scene file: colours, integers, inline materials and empty OBJs are validated",
          "[trace][scene][errors]") {
    using Catch::Contains;
    CHECK_THAT(load_error("color", R"({"camera": {"position": [0, 2, 5], "look_at": [0, 0, 0]},
        "lights": [{"center": [0, 3, 0], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1], "color": [1, -0.5, 1]}],
        "objects": [{"type": "sphere", "radius": 1}]})"),
               Contains("scene.json: lights[0].color: must not be negative"));
    // 2^32 + 7 would wrap to 7, a valid id, through a plain int conversion.
    CHECK_THAT(load_error("id_range", scene_text(R"([{"type": "sphere", "radius": 1, "id": 4294967303}])")),
               Contains("scene.json: objects[0].id: integer out of range"));
    CHECK_THAT(load_error("segments_range",
                          scene_text(R"([{"type": "sphere", "radius": 1, "segments": -4294967292}])")),
               Contains("scene.json: objects[0].segments: integer out of range"));
    CHECK_THAT(
        load_error("empty_material", scene_text(R"([{"type": "sphere", "radius": 1, "material": {}}])")),
        Contains("scene.json: objects[0].material: an inline material needs albedo, specular, roughness or "
                 "theta_max_deg"));
    CHECK_THAT(
        load_error("number_material", scene_text(R"([{"type": "sphere", "radius": 1, "material": 3}])")),
        Contains("scene.json: objects[0].material: expected a material name or an object"));
    CHECK_THAT(load_error("misspelt_material",
                          scene_text(R"([{"type": "sphere", "radius": 1, "material": {"albedoo": 0.5}}])")),
               Contains("scene.json: objects[0].material.albedoo: unknown field"));

    // An OBJ without faces is an error wherever it comes in the object list.
    const fs::path dir = scratch("empty_obj");
    write_file(dir / "points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    const std::string path =
        write_file(dir / "scene.json",
                   scene_text(R"([{"type": "sphere", "radius": 1}, {"type": "obj", "file": "points.obj"}])"));
    CHECK_THROWS_WITH(trace::load_scene_file(path, 16, 12),
                      Contains("objects[1].file: ") && Contains("no triangles"));
}

TEST_CASE("Scene file: values that would break Embree or overflow the radiance are refused",
          "[trace][scene][errors][limits]") {
    using Catch::Contains;
    auto with_light = [](const std::string &light) {
        return R"({"camera": {"position": [0, 2, 5], "look_at": [0, 0, 0]}, "lights": [)" + light +
               R"(], "objects": [{"type": "sphere", "radius": 1}]})";
    };
    auto with_camera = [](const std::string &camera) {
        return R"({"camera": )" + camera + R"(, "lights": [{"center": [0, 3, 0], "edge_u": [1, 0, 0],
                   "edge_v": [0, 0, 1]}], "objects": [{"type": "sphere", "radius": 1}]})";
    };
    // A light centre of 1e20 m reached Embree and aborted on its ray.valid() assertion.
    CHECK_THAT(load_error("far_light", with_light(R"({"center": [1e20, 3, 0], "edge_u": [1, 0, 0],
                                                   "edge_v": [0, 0, 1]})")),
               Contains("scene.json: lights[0].center: components must lie in [-1e+06, 1e+06] m"));
    CHECK_THAT(load_error("tiny_light", with_light(R"({"center": [0, 3, 0], "edge_u": [1e-9, 0, 0],
                                                    "edge_v": [0, 0, 1]})")),
               Contains("scene.json: lights[0]: edge_u and edge_v must be non-zero"));
    // 1e308 fits a double but becomes an infinite float: Inf pixels, exit 0.
    CHECK_THAT(load_error("bright", with_light(R"({"center": [0, 3, 0], "edge_u": [1, 0, 0],
                                                "edge_v": [0, 0, 1], "intensity": 1e308})")),
               Contains("scene.json: lights[0].intensity: expected a finite number"));
    CHECK_THAT(load_error("bright_1e10", with_light(R"({"center": [0, 3, 0], "edge_u": [1, 0, 0],
                                                     "edge_v": [0, 0, 1], "intensity": 1e10})")),
               Contains("scene.json: lights[0].intensity: must not exceed 1e+09 W/sr"));
    CHECK_THAT(load_error("colour", with_light(R"({"center": [0, 3, 0], "edge_u": [1, 0, 0],
                                                "edge_v": [0, 0, 1], "color": 1e4})")),
               Contains("scene.json: lights[0].color: must not exceed 1000"));
    CHECK_THAT(load_error("sigma", with_light(R"({"center": [0, 3, 0], "edge_u": [1, 0, 0],
                                               "edge_v": [0, 0, 1], "profile": "uniform", "sigma_m": 1e-30})")),
               Contains("scene.json: lights[0].sigma_m: must lie in [1e-06, 1e+06] m"));
    // A thin-lens aperture of 1e300 m aborted Embree the same way.
    CHECK_THAT(load_error("aperture", with_camera(R"({"type": "thin_lens", "position": [0, 2, 5],
                                                   "look_at": [0, 0, 0], "aperture_radius_m": 1e300})")),
               Contains("scene.json: camera.aperture_radius_m: expected a finite number"));
    CHECK_THAT(load_error("aperture_1e4", with_camera(R"({"type": "thin_lens", "position": [0, 2, 5],
                                                       "look_at": [0, 0, 0], "aperture_radius_m": 1e4})")),
               Contains("scene.json: camera.aperture_radius_m: must lie in [1e-06, 1000] m"));
    CHECK_THAT(load_error("focus", with_camera(R"({"type": "thin_lens", "position": [0, 2, 5],
                                                "look_at": [0, 0, 0], "aperture_radius_m": 0.1,
                                                "focus_distance_m": 1e7})")),
               Contains("scene.json: camera.focus_distance_m: must lie in [1e-06, 1e+06] m"));
    CHECK_THAT(load_error("eye", with_camera(R"({"position": [0, 2, -3e6], "look_at": [0, 0, 0]})")),
               Contains("scene.json: camera.position: components must lie in [-1e+06, 1e+06] m"));
    CHECK_THAT(load_error("fov", with_camera(R"({"position": [0, 2, 5], "look_at": [0, 0, 0],
                                              "fov_y_deg": 1e-30})")),
               Contains("scene.json: camera.fov_y_deg: must lie in [0.001, 180)"));
    // Each field within the bounds, the object beyond them after its transform.
    CHECK_THAT(
        load_error("translated", scene_text(R"([{"type": "sphere", "radius": 1,
                                                    "transform": {"translate": [1e6, 0, 0]}}])")),
        Contains("scene.json: objects[0]: reaches beyond 1e+06 m from the origin after its transform"));
    CHECK_THAT(load_error("scale", scene_text(R"([{"type": "box", "min": [0, 0, 0], "max": [1, 1, 1],
                                               "transform": {"scale": 1e20}}])")),
               Contains("scene.json: objects[0].transform.scale: scale must lie in [1e-12, 1e+12]"));
    CHECK_THAT(
        load_error("rotation", scene_text(R"([{"type": "sphere", "radius": 1,
                                                  "transform": {"rotate_deg": [0, 1e30, 0]}}])")),
        Contains(
            "scene.json: objects[0].transform.rotate_deg: components must lie in [-1e+06, 1e+06] degrees"));
    CHECK_THAT(load_error("thin", scene_text(R"([{"type": "cylinder", "radius": 1e-9, "height": 1}])")),
               Contains("scene.json: objects[0].radius: must lie in [1e-06, 1e+06] m"));
    CHECK_THAT(load_error("key_centre", scene_text(R"([{"type": "sphere", "radius": 1}])",
                                                   R"(, "animation": {"lights": [{"keys": [{"frame": 1,
                                                   "center": [0, 1e7, 0]}]}]})")),
               Contains("scene.json: animation.lights[0].keys[0].center: components must lie in"));
    CHECK_THAT(load_error("key_intensity", scene_text(R"([{"type": "sphere", "radius": 1}])",
                                                      R"(, "animation": {"lights": [{"keys": [{"frame": 1,
                                                      "intensity": 1e12}]}]})")),
               Contains("scene.json: animation.lights[0].keys[0].intensity: must not exceed 1e+09 W/sr"));
}

TEST_CASE("Scene file: a JSON number beyond double's range is one line naming the file",
          "[trace][scene][errors]") {
    const std::string message =
        load_error("overflow", scene_text(R"([{"type": "sphere", "radius": 1e400}])"));
    CHECK(message == (scratch_path("overflow") / "scene.json").string() +
                         ": invalid JSON: number overflow parsing '1e400'");
    // A raw control character inside a string: nlohmann quotes the text it read.
    const std::string raw =
        load_error("raw_newline", scene_text("[{\"type\": \"sph\nere\", \"radius\": 1}]"));
    CHECK_THAT(raw, Catch::Contains("scene.json: invalid JSON at line"));
    CHECK(raw.find('\n') == std::string::npos);
    // An escaped newline in a key is a real one once parsed: it stays escaped in the message.
    for (const char *objects : {R"([{"type": "sphere", "radius": 1, "a\nb": 2}])",
                                R"([{"type": "sphere", "radius": 1, "a\nb": 2, "a\nb": 3}])"}) {
        const std::string key = load_error("newline_key", scene_text(objects));
        CHECK_THAT(key, Catch::Contains("objects[0].a\\x0ab: "));
        CHECK(key.find('\n') == std::string::npos);
    }
}

TEST_CASE("Scene file: OBJ errors are one line naming the OBJ and the object",
          "[trace][scene][errors][obj]") {
    using Catch::Contains;
    const fs::path dir = scratch("obj_errors");
    write_file(dir / "bad_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
    write_file(dir / "far.obj", "v 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n");
    fs::create_directories(dir / "folder.obj");
    for (const auto &[file, problem] : {std::pair<std::string, std::string>{"bad_index.obj", "bad_index.obj"},
                                        {"far.obj", "objects[0]: reaches beyond 1e+06 m"},
                                        {"folder.obj", "objects[0].file: cannot open OBJ file"}}) {
        const std::string path =
            write_file(dir / "scene.json", scene_text(R"([{"type": "obj", "file": ")" + file + R"("}])"));
        INFO(file);
        try {
            trace::load_scene_file(path, 16, 12);
            FAIL("no error");
        } catch (const InputError &e) {
            const std::string message = e.what();
            CHECK_THAT(message, Contains(path + ": objects[0]") && Contains(problem));
            CHECK(message.find('\n') == std::string::npos);
        }
    }
}

TEST_CASE("Scene file: the files a scene reads are the scene and each OBJ it loads", "[trace][scene][obj]") {
    const fs::path dir = scratch("inputs");
    write_file(dir / "a.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    fs::create_directories(dir / "meshes");
    write_file(dir / "meshes" / "b.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nmtllib b.mtl\n");
    const std::string path = write_file(
        dir / "scene.json", scene_text(R"([{"type": "obj", "file": "a.obj"}, {"type": "sphere", "radius": 1},
                                           {"type": "obj", "file": "meshes/b.obj"}])"));
    CHECK(trace::scene_file_inputs(path) ==
          std::vector<std::string>{path, (dir / "a.obj").string(), (dir / "meshes" / "b.obj").string()});
    // The loader reads no other file: a material library the OBJ names is not opened.
    CHECK(trace::load_scene_file(path, 16, 12).meshes.size() == 3);
}

TEST_CASE("Scene names resolve to the shipped scene files", "[trace][scene]") {
    for (const char *name : {"grids", "spheres", "tentacles", "bench", "studio", "gallery", "tilted",
                             "grazing", "contact", "livingroom", "room"}) {
        const std::string path = trace::resolve_scene(name);
        INFO(name);
        CHECK(fs::path(path).filename() == std::string(name) + ".json");
        const trace::SceneDescription scene = trace::load_scene_file(path, 32, 24);
        CHECK(scene.name == name);
        CHECK(!scene.meshes.empty());
    }
    CHECK_THROWS_WITH(trace::resolve_scene("nope"), Catch::Contains("grids"));
}
