#include "scene_file.h"

#include <tiny_obj_loader.h>

#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>

#include "aaf/core/util/error.h"
#include "aaf/trace/light_file.h"
#include "aaf/trace/render.h"

namespace aaf::trace {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// The bounds every scene value keeps before it reaches Embree (SCENE_FORMAT.md,
// "Limits"). Embree asserts on rays whose origin or extent is too large for its
// float arithmetic (|origin| about 1.8e18), and a float's spacing at 1e6 m is
// already 6 cm, so a scene fits a cube of +-1e6 m; lengths below 1 micrometre
// make the pixel footprints and light pdfs underflow.
constexpr double kMaxCoordinate_m = 1e6;
constexpr double kMinLength_m = 1e-6;
constexpr double kMaxApertureRadius_m = 1e3;
constexpr double kMaxRotation_deg = 1e6;
// Radiance = intensity x colour x BRDF x cos x cos / r^2: with r >= 1e-6 m
// (1e12), a GGX peak of 1 / (pi 0.01^4) (3e7) and 1048576 samples summed,
// intensity x colour <= 1e12 keeps every sum below float's 3.4e38.
constexpr double kMaxIntensity_W_sr = 1e9;
constexpr double kMaxColor = 1e3;

/// `text` on one line: control characters (a raw newline from a parser or an
/// OBJ loader's message) become `\xNN`, a trailing newline goes.
std::string one_line(std::string text) {
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
    std::string line;
    for (const char c : text) {
        const auto byte = static_cast<unsigned char>(c);
        if (byte >= 0x20 && byte != 0x7f) {
            line += c;
            continue;
        }
        char escaped[8];
        std::snprintf(escaped, sizeof escaped, "\\x%02x", byte);
        line += escaped;
    }
    return line;
}

/// A bound as the messages print it: 1e+06 -> "1e+06", 0.001 -> "0.001".
std::string bound_text(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}

/// A JSON value with the path that leads to it, so every error can say where
/// in which file the problem is ("scene.json: objects[2].radius: ...").
class Node {
  public:
    Node(const json &value, std::string path, const std::string &file)
        : value_(value), path_(std::move(path)), file_(file) {}

    [[noreturn]] void fail(const std::string &problem) const {
        throw InputError(one_line(file_ + ": " + (path_.empty() ? "" : path_ + ": ") + problem));
    }

    bool has(const char *key) const { return value_.is_object() && value_.contains(key); }
    bool is_object() const { return value_.is_object(); }
    bool is_string() const { return value_.is_string(); }
    Node at(const char *key) const {
        if (!value_.is_object()) fail("expected an object");
        if (!value_.contains(key)) fail(std::string("missing required field '") + key + "'");
        return child(key);
    }
    std::optional<Node> find(const char *key) const {
        if (!has(key)) return std::nullopt;
        return child(key);
    }
    std::vector<std::string> keys() const {
        if (!value_.is_object()) fail("expected an object");
        std::vector<std::string> names;
        for (const auto &item : value_.items()) names.push_back(item.key());
        return names;
    }
    std::size_t size() const {
        if (!value_.is_array()) fail("expected an array");
        return value_.size();
    }
    Node operator[](std::size_t index) const {
        return Node(value_.at(index), path_ + "[" + std::to_string(index) + "]", file_);
    }
    /// Rejects keys outside `allowed`, so a misspelt field is an error, not a silent default.
    void allow_only(std::initializer_list<const char *> allowed) const {
        if (!value_.is_object()) fail("expected an object");
        const std::set<std::string> known(allowed.begin(), allowed.end());
        for (const auto &item : value_.items())
            if (!known.count(item.key())) child(item.key().c_str()).fail("unknown field");
    }

    float number() const {
        if (!value_.is_number()) fail("expected a number");
        const double v = value_.get<double>();
        // Beyond float's range the value would become infinite on conversion.
        if (!(std::fabs(v) <= std::numeric_limits<float>::max())) fail("expected a finite number");
        return float(v);
    }
    float positive() const {
        const float v = number();
        if (!(v > 0)) fail("must be positive");
        return v;
    }
    /// A number in [lo, hi]; `unit` follows the bounds in the message.
    float number_in(double lo, double hi, const char *unit = "") const {
        const float v = number();
        if (!(v >= float(lo) && v <= float(hi)))
            fail("must lie in [" + bound_text(lo) + ", " + bound_text(hi) + "]" + unit);
        return v;
    }
    /// A length in metres: positive, in [kMinLength_m, max_m].
    float length_m(double max_m = kMaxCoordinate_m) const {
        positive();  // a zero or negative length says so first
        return number_in(kMinLength_m, max_m, " m");
    }
    int integer() const {
        if (!value_.is_number_integer()) fail("expected an integer");
        // get<int> would wrap a larger value silently.
        const bool in_range =
            value_.is_number_unsigned()
                ? value_.get<std::uint64_t>() <= std::uint64_t(INT_MAX)
                : value_.get<std::int64_t>() >= INT_MIN && value_.get<std::int64_t>() <= INT_MAX;
        if (!in_range) fail("integer out of range");
        return value_.get<int>();
    }
    bool boolean() const {
        if (!value_.is_boolean()) fail("expected true or false");
        return value_.get<bool>();
    }
    std::string string() const {
        if (!value_.is_string()) fail("expected a string");
        return value_.get<std::string>();
    }
    Vec3 vec3() const {
        if (!value_.is_array() || value_.size() != 3) fail("expected an array of 3 numbers");
        return {(*this)[0].number(), (*this)[1].number(), (*this)[2].number()};
    }
    /// A 3-vector whose components lie in [-bound, bound].
    Vec3 vec3_within(double bound, const char *unit) const {
        const Vec3 v = vec3();
        for (int c = 0; c < 3; ++c)
            if (!(std::fabs(v[c]) <= bound))
                fail("components must lie in [-" + bound_text(bound) + ", " + bound_text(bound) + "]" + unit);
        return v;
    }
    /// A point or offset in world metres, within kMaxCoordinate_m per axis.
    Vec3 point() const { return vec3_within(kMaxCoordinate_m, " m"); }
    /// A 3-vector, or one number for all three components.
    Vec3 vec3_or_scalar() const {
        if (value_.is_number()) {
            const float v = number();
            return {v, v, v};
        }
        return vec3();
    }

  private:
    Node child(const std::string &key) const {
        return Node(value_.at(key), path_.empty() ? key : path_ + "." + key, file_);
    }
    const json &value_;
    std::string path_;
    const std::string &file_;
};

/// Rejects a key repeated within one JSON object (nlohmann keeps the last
/// silently, so a second "camera" track would hide the first), naming its path.
class DuplicateKeyCheck {
  public:
    explicit DuplicateKeyCheck(const std::string &file) : file_(file) {}

    bool operator()(int, json::parse_event_t event, json &parsed) {
        using Event = json::parse_event_t;
        if ((event == Event::object_start || event == Event::array_start || event == Event::value) &&
            !levels_.empty() && levels_.back().is_array)
            ++levels_.back().index;
        if (event == Event::object_start || event == Event::array_start)
            levels_.push_back({event == Event::array_start, -1, {}, {}});
        else if (event == Event::object_end || event == Event::array_end)
            levels_.pop_back();
        else if (event == Event::key && !levels_.empty()) {
            Level &level = levels_.back();
            level.key = parsed.get<std::string>();
            if (!level.keys.insert(level.key).second)
                throw InputError(one_line(file_ + ": " + path() + ": duplicate key (give each field once)"));
        }
        return true;
    }

  private:
    struct Level {
        bool is_array;
        int index;        ///< arrays: the element being parsed
        std::string key;  ///< objects: the key being parsed
        std::set<std::string> keys;
    };
    std::string path() const {
        std::string text;
        for (const Level &level : levels_)
            text += level.is_array ? "[" + std::to_string(level.index) + "]"
                                   : (text.empty() ? "" : ".") + level.key;
        return text;
    }
    const std::string &file_;
    std::vector<Level> levels_;
};

json parse_json_file(const std::string &path) {
    // A folder reads as empty and a device such as /dev/zero never ends; a
    // pipe (a scene from process substitution) is fine.
    std::error_code error;
    const fs::file_type type = fs::status(path, error).type();
    if (type != fs::file_type::regular && type != fs::file_type::fifo && type != fs::file_type::not_found)
        throw InputError(one_line(path + ": cannot open scene file (a folder or device, not a file)"));
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(one_line(path + ": cannot open scene file"));
    std::stringstream text;
    text << in.rdbuf();
    try {
        return json::parse(text.str(), DuplicateKeyCheck(path));
    } catch (const json::exception &e) {
        // nlohmann's messages read "[json.exception.parse_error.101] parse error at
        // line L, column C: ..." or, for a number beyond double's range such as
        // 1e400, "[json.exception.out_of_range.406] number overflow parsing '1e400'".
        std::string message = e.what();
        const auto at = message.find("at line");
        const auto tag_end = message.find("] ");
        if (at != std::string::npos)
            message = " " + message.substr(at);
        else
            message = ": " + (tag_end == std::string::npos ? message : message.substr(tag_end + 2));
        throw InputError(one_line(path + ": invalid JSON" + message));
    }
}

Material read_material(const Node &node) {
    node.allow_only({"albedo", "specular", "roughness", "theta_max_deg", "checker", "bump"});
    Material material;
    if (auto albedo = node.find("albedo")) material.albedo = albedo->vec3_or_scalar();
    if (auto specular = node.find("specular")) material.specular = specular->vec3_or_scalar();
    if (auto roughness = node.find("roughness")) material.roughness = roughness->number();
    if (auto theta = node.find("theta_max_deg")) material.theta_max_deg = theta->number();
    if (auto checker = node.find("checker")) {
        checker->allow_only({"size_m", "albedo"});
        material.checker_size_m = checker->at("size_m").number();
        if (!(material.checker_size_m >= 1e-4f && material.checker_size_m <= 1e4f))
            checker->at("size_m").fail("checker size_m must lie in [1e-4, 1e4] metres");
        if (auto second = checker->find("albedo")) material.checker_albedo = second->vec3_or_scalar();
        for (int c = 0; c < 3; ++c)
            if (material.checker_albedo[c] < 0 || material.checker_albedo[c] > 1)
                checker->fail("checker albedo must lie in [0, 1]");
    }
    if (auto bump = node.find("bump")) {
        bump->allow_only({"slope", "period_m"});
        material.bump_slope = bump->at("slope").number();
        if (auto period = bump->find("period_m")) material.bump_period_m = period->number();
        if (!(material.bump_slope >= 0 && material.bump_slope <= 10))
            bump->fail("bump slope must lie in [0, 10]");
        if (!(material.bump_period_m >= 1e-4f && material.bump_period_m <= 1e4f))
            bump->fail("bump period_m must lie in [1e-4, 1e4] metres");
    }
    for (int c = 0; c < 3; ++c)
        if (material.albedo[c] < 0 || material.albedo[c] > 1 || material.specular[c] < 0 ||
            material.specular[c] > 1)
            node.fail("albedo and specular must lie in [0, 1]");
    if (!(material.roughness >= 0.01f && material.roughness <= 1))
        node.fail("roughness must lie in [0.01, 1]");
    if (!(material.theta_max_deg >= 0 && material.theta_max_deg <= 60))
        node.fail("theta_max_deg must lie in [0, 60]");
    return material;
}

Transform read_transform(const std::optional<Node> &node) {
    if (!node) return {};
    node->allow_only({"scale", "rotate_deg", "translate"});
    Vec3 scale{1, 1, 1}, rotate{0, 0, 0}, translate{0, 0, 0};
    if (auto s = node->find("scale")) {
        scale = s->vec3_or_scalar();
        if (!(scale.x > 0 && scale.y > 0 && scale.z > 0)) s->fail("scale must be positive");
        // A scale is a ratio of lengths: it keeps to the lengths' range.
        const double max_scale = kMaxCoordinate_m / kMinLength_m;
        for (int c = 0; c < 3; ++c)
            if (!(scale[c] >= float(1 / max_scale) && scale[c] <= float(max_scale)))
                s->fail("scale must lie in [" + bound_text(1 / max_scale) + ", " + bound_text(max_scale) +
                        "]");
    }
    if (auto r = node->find("rotate_deg")) rotate = r->vec3_within(kMaxRotation_deg, " degrees");
    if (auto t = node->find("translate")) translate = t->point();
    return Transform::from(scale, rotate, translate);
}

/// A light's intensity, W/sr: in [0, kMaxIntensity_W_sr].
float read_intensity(const Node &node) {
    const float intensity = node.number();
    if (intensity < 0) node.fail("must not be negative");
    if (!(intensity <= kMaxIntensity_W_sr))
        node.fail("must not exceed " + bound_text(kMaxIntensity_W_sr) +
                  " W/sr (see SCENE_FORMAT.md, Limits)");
    return intensity;
}

SceneLight read_light(const Node &node) {
    node.allow_only({"center", "edge_u", "edge_v", "intensity", "color", "profile", "sigma_m"});
    SceneLight light;
    LightPlane &plane = light.plane;
    plane.center = node.at("center").point();
    const Vec3 edge_u = node.at("edge_u").point(), edge_v = node.at("edge_v").point();
    plane.width_m = length(edge_u);
    plane.height_m = length(edge_v);
    if (!(plane.width_m >= float(kMinLength_m)) || !(plane.height_m >= float(kMinLength_m)))
        node.fail("edge_u and edge_v must be non-zero (" + bound_text(kMinLength_m) + " m or longer)");
    plane.axis_u = edge_u / plane.width_m;
    plane.axis_v = edge_v / plane.height_m;
    if (std::fabs(dot(plane.axis_u, plane.axis_v)) > 1e-3f) node.fail("edge_u and edge_v must be orthogonal");
    // The light emits towards edge_u x edge_v.
    plane.normal = normalize(cross(plane.axis_u, plane.axis_v));
    // Default sigma: half the shorter side (for a square, sigma = L / 2: light_plane.h).
    plane.sigma_m = 0.5f * std::min(plane.width_m, plane.height_m);
    if (auto sigma = node.find("sigma_m")) plane.sigma_m = sigma->length_m();
    if (auto profile = node.find("profile")) {
        const std::string name = profile->string();
        if (name != "gaussian" && name != "uniform") profile->fail("expected \"gaussian\" or \"uniform\"");
        plane.profile = light_profile_from_string(name);
    }
    if (plane.profile == LightProfile::Gaussian &&
        std::max(plane.width_m, plane.height_m) > 16 * plane.sigma_m)
        node.fail("sigma_m is too small for the light's size (the Gaussian is truncated beyond 8 sigma)");
    if (auto intensity = node.find("intensity")) light.intensity = read_intensity(*intensity);
    if (auto color = node.find("color")) {
        light.color = color->vec3_or_scalar();
        if (light.color.x < 0 || light.color.y < 0 || light.color.z < 0) color->fail("must not be negative");
        for (int c = 0; c < 3; ++c)
            if (!(light.color[c] <= kMaxColor))
                color->fail("must not exceed " + bound_text(kMaxColor) + " (see SCENE_FORMAT.md, Limits)");
    }
    return light;
}

/// The checks a camera key must pass, static or animated; `node` is where
/// the key was read, `fov` and its field when it gave one.
void check_camera_key(const Node &node, const CameraKey &key, Vec3 up, const std::optional<Node> &fov) {
    if (!(length(key.target - key.eye) >= float(kMinLength_m)))
        node.fail("position and look_at must differ (by " + bound_text(kMinLength_m) + " m or more)");
    if (!(length(cross(normalize(key.target - key.eye), up)) > 1e-4f))
        node.fail("up must not be parallel to the view");
    // Below a thousandth of a degree the pixel footprints underflow.
    if (fov && !(key.fov_y_deg >= 1e-3f && key.fov_y_deg < 180)) fov->fail("must lie in [0.001, 180)");
}

Camera read_camera(const Node &node, int width, int height, CameraKey &key, Vec3 &up) {
    node.allow_only(
        {"type", "position", "look_at", "up", "fov_y_deg", "aperture_radius_m", "focus_distance_m"});
    const std::string type = node.has("type") ? node.at("type").string() : "pinhole";
    if (type != "pinhole" && type != "thin_lens")
        node.at("type").fail("expected \"pinhole\" or \"thin_lens\"");
    key.eye = node.at("position").point();
    key.target = node.at("look_at").point();
    if (auto u = node.find("up")) up = u->point();
    const std::optional<Node> fov = node.find("fov_y_deg");
    if (fov) key.fov_y_deg = fov->number();
    check_camera_key(node, key, up, fov);
    key.focus_distance_m = length(key.target - key.eye);
    if (auto focus = node.find("focus_distance_m")) key.focus_distance_m = focus->length_m();
    Camera camera = Camera::look_at(key.eye, key.target, up, key.fov_y_deg, width, height);
    camera.focus_distance_m = key.focus_distance_m;
    if (type == "thin_lens")
        camera.aperture_radius_m = node.at("aperture_radius_m").length_m(kMaxApertureRadius_m);
    else if (node.has("aperture_radius_m"))
        node.at("aperture_radius_m").fail("only a thin_lens camera has an aperture");
    return camera;
}

/// Appends the triangles of an OBJ file as one mesh, or one mesh per OBJ
/// shape with consecutive ids when `mesh_per_shape`.
void load_obj(const Node &node, const fs::path &file, const Mesh &prototype, const Transform &to_world,
              bool mesh_per_shape, std::vector<Mesh> &meshes) {
    std::ifstream in(file, std::ios::binary);
    if (!fs::is_regular_file(file) || !in) node.fail("cannot open OBJ file '" + file.string() + "'");
    std::stringstream text;
    text << in.rdbuf();
    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    // Parsed from memory with no material text: the scene gives the materials,
    // so the only file an OBJ object reads is its own (scene_file_inputs()).
    if (!reader.ParseFromString(text.str(), "", config)) node.fail(file.string() + ": " + reader.Error());
    const std::vector<tinyobj::real_t> &vertices = reader.GetAttrib().vertices;
    const std::size_t vertex_count = vertices.size() / 3;
    const std::size_t meshes_before = meshes.size();
    Mesh mesh = prototype;
    std::vector<std::int64_t> local(vertex_count, -1);  // OBJ vertex -> index in `mesh`
    int shape_index = 0;
    for (const tinyobj::shape_t &shape : reader.GetShapes()) {
        for (const tinyobj::index_t &index : shape.mesh.indices) {
            if (index.vertex_index < 0 || std::size_t(index.vertex_index) >= vertex_count)
                node.fail(file.string() + ": shape '" + shape.name + "' has a vertex index out of range");
            std::int64_t &slot = local[std::size_t(index.vertex_index)];
            if (slot < 0) {
                slot = std::int64_t(mesh.positions.size());
                const float *v = &vertices[3 * std::size_t(index.vertex_index)];
                mesh.positions.push_back(to_world.apply({v[0], v[1], v[2]}));
            }
            mesh.indices.push_back(std::uint32_t(slot));
        }
        if (mesh_per_shape && !mesh.indices.empty()) {
            meshes.push_back(std::move(mesh));
            mesh = prototype;
            mesh.object_id = prototype.object_id + ++shape_index;
            std::fill(local.begin(), local.end(), -1);
        }
    }
    if (!mesh.indices.empty()) meshes.push_back(std::move(mesh));
    if (meshes.size() == meshes_before) node.fail(file.string() + ": no triangles");
}

/// Refuses an object any of whose vertices (after its transform) lies
/// outside the scene's cube of +-kMaxCoordinate_m, or is not a number.
void check_within_scene(const Node &node, const std::vector<Mesh> &meshes, std::size_t first_mesh) {
    for (std::size_t m = first_mesh; m < meshes.size(); ++m)
        for (const Vec3 &p : meshes[m].positions)
            for (int c = 0; c < 3; ++c)
                if (!(std::fabs(p[c]) <= kMaxCoordinate_m))
                    node.fail("reaches beyond " + bound_text(kMaxCoordinate_m) +
                              " m from the origin after its transform (see SCENE_FORMAT.md, Limits)");
}

void read_object(const Node &node, const fs::path &scene_dir,
                 const std::map<std::string, Material> &materials, int default_id,
                 std::vector<Mesh> &meshes) {
    const std::string type = node.at("type").string();
    Mesh mesh;
    mesh.object_id = default_id;
    if (auto id = node.find("id")) {
        mesh.object_id = id->integer();
        if (mesh.object_id < 1 || mesh.object_id > (1 << 24)) id->fail("must lie in [1, 16777216]");
    }
    if (auto material = node.find("material")) {
        if (material->is_object()) {
            if (material->keys().empty())
                material->fail(
                    "an inline material needs albedo, specular, roughness or theta_max_deg (or give a name)");
            mesh.material = read_material(*material);
        } else if (material->is_string()) {
            auto it = materials.find(material->string());
            if (it == materials.end()) material->fail("unknown material '" + material->string() + "'");
            mesh.material = it->second;
        } else {
            material->fail("expected a material name or an object with albedo, specular, roughness");
        }
    }
    const Transform to_world = read_transform(node.find("transform"));
    if (type == "plane") {
        node.allow_only({"type", "id", "material", "transform", "size"});
        float half_x = 0.5f, half_z = 0.5f;
        if (auto size = node.find("size")) {
            if (size->size() != 2) size->fail("expected [size_x, size_z]");
            half_x = 0.5f * (*size)[0].length_m();
            half_z = 0.5f * (*size)[1].length_m();
        }
        // Normal +y (the winding does not matter: shading faces the camera).
        mesh.add_quad(to_world.apply({-half_x, 0, -half_z}), to_world.apply({-half_x, 0, half_z}),
                      to_world.apply({half_x, 0, half_z}), to_world.apply({half_x, 0, -half_z}));
    } else if (type == "box") {
        node.allow_only({"type", "id", "material", "transform", "min", "max"});
        const Vec3 lo = node.at("min").point(), hi = node.at("max").point();
        if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z)) node.fail("min must be below max on every axis");
        mesh.add_box(lo, hi, to_world);
    } else if (type == "sphere") {
        node.allow_only({"type", "id", "material", "transform", "center", "radius", "segments"});
        const Vec3 center = node.has("center") ? node.at("center").point() : Vec3{};
        const int segments = node.has("segments") ? node.at("segments").integer() : 48;
        if (segments < 4 || segments > 4096) node.at("segments").fail("must lie in [4, 4096]");
        mesh.add_sphere(center, node.at("radius").length_m(), segments, to_world);
    } else if (type == "cylinder") {
        node.allow_only({"type", "id", "material", "transform", "radius", "height", "segments"});
        const int segments = node.has("segments") ? node.at("segments").integer() : 32;
        if (segments < 3 || segments > 4096) node.at("segments").fail("must lie in [3, 4096]");
        mesh.add_cylinder(node.at("radius").length_m(), node.at("height").length_m(), segments, to_world);
    } else if (type == "obj") {
        node.allow_only({"type", "id", "material", "transform", "file", "id_per_shape"});
        const bool per_shape = node.has("id_per_shape") && node.at("id_per_shape").boolean();
        load_obj(node.at("file"), scene_dir / node.at("file").string(), mesh, to_world, per_shape, meshes);
        return;
    } else {
        node.at("type").fail("unknown object type '" + type +
                             "' (expected plane, box, sphere, cylinder or obj)");
    }
    meshes.push_back(std::move(mesh));
}

/// Keys of one track, checked to have strictly increasing frames.
template <typename Key, typename ReadKey>
std::vector<Key> read_keys(const Node &node, const ReadKey &read_key) {
    std::vector<Key> keys;
    for (std::size_t i = 0; i < node.size(); ++i) {
        Key key = read_key(node[i]);
        key.frame = node[i].at("frame").number();
        if (!keys.empty() && !(key.frame > keys.back().frame))
            node[i].at("frame").fail("frames must increase");
        keys.push_back(key);
    }
    if (keys.empty()) node.fail("expected at least one key");
    return keys;
}

/// `object_meshes[i]`: the meshes objects[i] of the file became, [first, last).
void read_animation(const Node &node, SceneDescription &scene, const CameraKey &static_camera,
                    const std::vector<std::pair<std::size_t, std::size_t>> &object_meshes) {
    node.allow_only({"camera", "lights", "objects"});
    if (auto camera = node.find("camera"))
        scene.animation.camera = read_keys<CameraKey>(*camera, [&](const Node &key_node) {
            key_node.allow_only({"frame", "position", "look_at", "fov_y_deg", "focus_distance_m"});
            CameraKey key = static_camera;
            if (auto p = key_node.find("position")) key.eye = p->point();
            if (auto t = key_node.find("look_at")) key.target = t->point();
            const std::optional<Node> fov = key_node.find("fov_y_deg");
            if (fov) key.fov_y_deg = fov->number();
            if (auto f = key_node.find("focus_distance_m")) key.focus_distance_m = f->length_m();
            check_camera_key(key_node, key, scene.animation.camera_up, fov);
            return key;
        });
    if (auto lights = node.find("lights")) {
        scene.animation.lights.resize(scene.lights.size());
        for (std::size_t i = 0; i < lights->size(); ++i) {
            const Node track = (*lights)[i];
            track.allow_only({"light", "keys"});
            const int index = track.has("light") ? track.at("light").integer() : 0;
            if (index < 0 || std::size_t(index) >= scene.lights.size())
                track.at("light").fail("no such light");
            if (!scene.animation.lights[std::size_t(index)].empty())
                track.fail("light " + std::to_string(index) + " already has a track");
            const SceneLight &light = scene.lights[std::size_t(index)];
            scene.animation.lights[std::size_t(index)] =
                read_keys<LightKey>(track.at("keys"), [&](const Node &key_node) {
                    key_node.allow_only({"frame", "center", "intensity"});
                    LightKey key;
                    key.center = key_node.has("center") ? key_node.at("center").point() : light.plane.center;
                    key.intensity = light.intensity;
                    if (auto intensity = key_node.find("intensity"))
                        key.intensity = read_intensity(*intensity);
                    return key;
                });
        }
    }
    if (auto objects = node.find("objects")) {
        scene.animation.meshes.resize(scene.meshes.size());
        for (std::size_t i = 0; i < objects->size(); ++i) {
            const Node track = (*objects)[i];
            track.allow_only({"object", "keys"});
            const int index = track.at("object").integer();
            if (index < 0 || std::size_t(index) >= object_meshes.size())
                track.at("object").fail("no such object");
            const auto [first, last] = object_meshes[std::size_t(index)];
            if (first < last && !scene.animation.meshes[first].empty())
                track.fail("object " + std::to_string(index) + " already has a track");
            const std::vector<ObjectKey> keys =
                read_keys<ObjectKey>(track.at("keys"), [](const Node &key_node) {
                    key_node.allow_only({"frame", "offset"});
                    ObjectKey key;
                    key.offset_m = key_node.at("offset").point();
                    return key;
                });
            for (std::size_t m = first; m < last; ++m) scene.animation.meshes[m] = keys;
        }
    }
}

}  // namespace

SceneDescription load_scene_file(const std::string &path, int width, int height) {
    const json document = parse_json_file(path);
    const Node root(document, "", path);
    root.allow_only({"format_version", "name", "camera", "materials", "lights", "objects", "animation"});
    if (auto version = root.find("format_version"))
        if (version->integer() != 1) version->fail("unsupported format version (this build reads 1)");

    SceneDescription scene;
    scene.source = path;
    scene.name = root.has("name") ? root.at("name").string() : fs::path(path).stem().string();

    CameraKey camera_key;
    scene.camera = read_camera(root.at("camera"), width, height, camera_key, scene.animation.camera_up);

    std::map<std::string, Material> materials;
    if (auto table = root.find("materials"))
        for (const std::string &name : table->keys())
            materials[name] = read_material(table->at(name.c_str()));

    const Node lights = root.at("lights");
    if (lights.size() == 0) lights.fail("a scene needs at least one light");
    for (std::size_t i = 0; i < lights.size(); ++i) scene.lights.push_back(read_light(lights[i]));

    const Node objects = root.at("objects");
    if (objects.size() == 0) objects.fail("a scene needs at least one object");
    const fs::path scene_dir = fs::path(path).parent_path();
    std::vector<std::pair<std::size_t, std::size_t>> object_meshes;
    for (std::size_t i = 0; i < objects.size(); ++i) {
        const std::size_t meshes_before = scene.meshes.size();
        read_object(objects[i], scene_dir, materials, int(i) + 1, scene.meshes);
        check_within_scene(objects[i], scene.meshes, meshes_before);
        object_meshes.emplace_back(meshes_before, scene.meshes.size());
    }

    if (auto animation = root.find("animation")) read_animation(*animation, scene, camera_key, object_meshes);
    return scene;
}

LightPlane load_light_file(const std::string &path) {
    const json document = parse_json_file(path);
    const Node root(document, "", path);
    if (!root.has("lights")) return read_light(root).plane;
    const Node lights = root.at("lights");
    if (lights.size() == 0) lights.fail("a scene needs at least one light");
    return read_light(lights[0]).plane;
}

std::vector<std::string> scene_file_inputs(const std::string &path) {
    std::vector<std::string> files{path};
    // A pipe can be read once, by the loader; its OBJ paths could only be absolute.
    std::error_code error;
    if (fs::status(path, error).type() == fs::file_type::fifo) return files;
    const json document = parse_json_file(path);
    const auto objects = document.is_object() ? document.find("objects") : document.end();
    if (objects == document.end() || !objects->is_array()) return files;
    const fs::path scene_dir = fs::path(path).parent_path();
    for (const json &object : *objects) {
        if (!object.is_object()) continue;
        const auto type = object.find("type"), file = object.find("file");
        if (type != object.end() && *type == "obj" && file != object.end() && file->is_string())
            files.push_back((scene_dir / file->get<std::string>()).string());
    }
    return files;
}

std::vector<std::string> scene_directories() {
    std::vector<std::string> dirs;
    if (const char *env = std::getenv("AAF_SCENE_PATH")) {
        std::stringstream list(env);
        for (std::string dir; std::getline(list, dir, ':');)
            if (!dir.empty()) dirs.push_back(dir);
    }
    // Relative to the running program first, so an installed tree that was
    // moved (or installed under another prefix) still finds its own scenes.
    std::error_code error;
    const fs::path program = fs::read_symlink("/proc/self/exe", error);
    if (!error)
        dirs.push_back((program.parent_path() / AAF_SCENE_DIR_FROM_BINARY).lexically_normal().string());
    dirs.push_back(AAF_INSTALLED_SCENE_DIR);
    dirs.push_back(AAF_SOURCE_SCENE_DIR);
    return dirs;
}

std::vector<std::string> builtin_scene_names() {
    std::set<std::string> names;
    for (const std::string &dir : scene_directories()) {
        std::error_code error;
        for (const auto &entry : fs::directory_iterator(dir, error))
            if (entry.path().extension() == ".json") names.insert(entry.path().stem().string());
    }
    return {names.begin(), names.end()};
}

std::string resolve_scene(const std::string &name_or_path) {
    const bool is_path =
        name_or_path.find('/') != std::string::npos || fs::path(name_or_path).extension() == ".json";
    if (is_path) return name_or_path;
    for (const std::string &dir : scene_directories()) {
        const fs::path candidate = fs::path(dir) / (name_or_path + ".json");
        if (fs::is_regular_file(candidate)) return candidate.string();
    }
    std::string known;
    for (const std::string &name : builtin_scene_names()) known += (known.empty() ? "" : ", ") + name;
    throw InputError("unknown scene '" + name_or_path +
                     "' (scenes: " + (known.empty() ? "none found" : known) + "; or give a .json file)");
}

}  // namespace aaf::trace
