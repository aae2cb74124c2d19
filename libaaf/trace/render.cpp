#include "aaf/trace/render.h"

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "aaf/core/aov_contract.h"
#include "aaf/core/error.h"
#include "embree_scene.h"
#include "light_sampler.h"
#include "random.h"
#include "scene_description.h"

namespace aaf::trace {

namespace {

constexpr float kPi = 3.14159265358979323846f;
constexpr int kTileSize = 16;

/// What the primary ray through a pixel's centre sees.
struct PrimaryHit {
    bool found = false;
    Vec3 position;           ///< world metres
    Vec3 normal;             ///< unit geometric normal, facing the camera
    const Mesh *mesh = nullptr;
    float pixel_size_m = 0;  ///< d of AAF Eq. 6
    Vec3 unshadowed;         ///< r(x) of AAF Eq. 1
};

/// Shadow-ray statistics of one pixel.
struct ShadowStats {
    std::uint32_t taken = 0;
    std::uint32_t unoccluded = 0;
    float d2_min_m = std::numeric_limits<float>::infinity();
    float d2_max_m = 0;

    void add_occluder(float d2_m) {
        d2_min_m = std::min(d2_min_m, d2_m);
        d2_max_m = std::max(d2_max_m, d2_m);
    }
    bool occluded_any() const { return d2_max_m > 0; }
    float visibility() const { return taken ? float(unoccluded) / float(taken) : 1.0f; }
};

class Renderer {
  public:
    Renderer(const SceneDescription &scene, const RenderSettings &settings)
        : scene_(scene), settings_(settings), bvh_(scene), light_sampler_(scene.light) {}

    PrimaryHit trace_primary(int x, int y) const {
        const PinholeCamera &camera = scene_.camera;
        const Vec3 direction = camera.ray_direction(x + 0.5f, y + 0.5f);
        const Hit hit = bvh_.intersect(camera.eye, direction, 0.0f, std::numeric_limits<float>::infinity());
        PrimaryHit primary;
        if (!hit.found) return primary;
        primary.found = true;
        primary.mesh = &scene_.meshes[hit.mesh_index];
        primary.position = camera.eye + direction * hit.distance;
        Vec3 normal = normalize(hit.geometric_normal);
        primary.normal = dot(normal, direction) > 0 ? -normal : normal;
        primary.pixel_size_m = pixel_footprint(primary, x, y);

        // AAF Eq. 1: the light's irradiance evaluated at its centre, no visibility.
        const LightPlane &light = scene_.light;
        Vec3 to_light = light.center - primary.position;
        const float distance_sq = dot(to_light, to_light);
        to_light = to_light / std::sqrt(distance_sq);
        const float cos_receiver = std::max(0.0f, dot(primary.normal, to_light));
        const float cos_light = std::max(0.0f, -dot(light.normal, to_light));
        const float irradiance = scene_.light_intensity * cos_receiver * cos_light / distance_sq;
        primary.unshadowed = primary.mesh->albedo * (irradiance / kPi);
        return primary;
    }

    /// Traces `count` shadow rays of pass `pass` and adds them to `stats`.
    void trace_shadows(const PrimaryHit &primary, std::uint64_t pixel_index, std::uint32_t pass,
                       std::uint32_t count, ShadowStats &stats) const {
        const LightPlane &light = scene_.light;
        PixelRng rng(settings_.seed, pixel_index, pass);
        const std::uint32_t stratum_key = rng.next_u32();
        // Offset along the camera-facing normal, scaled to the coordinates' magnitude.
        const Vec3 p = primary.position;
        const float epsilon = 1e-4f * (1.0f + std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)}));
        const Vec3 origin = p + primary.normal * epsilon;
        const float d1 = light.plane_distance_m(p);
        for (std::uint32_t i = 0; i < count; ++i) {
            const float u1 = rng.next_float(), u2 = rng.next_float();
            const Vec3 target = light_sampler_.sample(i, count, stratum_key, u1, u2);
            ++stats.taken;
            const Vec3 direction = target - origin;
            if (dot(primary.normal, target - p) <= 0) {
                // The light point lies behind the receiver's own tangent plane: self-occlusion.
                stats.add_occluder(d1);
                continue;
            }
            // Parameter 1 reaches the light point; the light itself is not in the BVH.
            const Hit hit = bvh_.intersect(origin, direction, 0.0f, 1.0f);
            if (!hit.found) {
                ++stats.unoccluded;
                continue;
            }
            stats.add_occluder(light.plane_distance_m(origin + direction * hit.distance));
        }
    }

  private:
    /// World size of the pixel at the hit: the rays through the neighbouring
    /// pixel centres meet the hit's tangent plane; d = sqrt(|dP/dx x dP/dy|),
    /// which includes foreshortening.
    float pixel_footprint(const PrimaryHit &primary, int x, int y) const {
        const PinholeCamera &camera = scene_.camera;
        const Vec3 n = primary.normal;
        const float plane_offset = dot(n, primary.position - camera.eye);
        auto on_plane = [&](Vec3 direction) {
            // Grazing rays are clamped to a 1e-3 cosine so the footprint stays finite.
            const float cosine = dot(n, direction);
            const float limit = 1e-3f * length(direction);
            const float denominator = std::fabs(cosine) < limit ? std::copysign(limit, cosine) : cosine;
            return camera.eye + direction * (plane_offset / denominator);
        };
        const Vec3 dx = on_plane(camera.ray_direction(x + 1.5f, y + 0.5f)) - primary.position;
        const Vec3 dy = on_plane(camera.ray_direction(x + 0.5f, y + 1.5f)) - primary.position;
        return std::sqrt(length(cross(dx, dy)));
    }

    const SceneDescription &scene_;
    const RenderSettings &settings_;
    EmbreeScene bvh_;
    LightSampler light_sampler_;
};

void validate(const RenderSettings &settings) {
    if (settings.width < 1 || settings.width > 16384 || settings.height < 1 || settings.height > 16384)
        throw Error("image size must lie in [1, 16384] pixels per side");
    if (settings.spp < 1 || settings.spp > (1 << 20)) throw Error("spp must lie in [1, 1048576]");
    if (settings.threads < 0) throw Error("threads must be >= 0");
}

/// Writable views of the contract's channels for one role.
std::vector<PlaneView> role_channels(AovSet &aovs, Role role) {
    std::vector<PlaneView> views;
    for (const std::string &name : role_info(role).channels) views.push_back(aovs.add_channel(name));
    return views;
}

}  // namespace

std::vector<std::string> builtin_scene_names() { return {"grids"}; }

AovSet render_builtin(const std::string &scene_name, const RenderSettings &settings) {
    validate(settings);
    const std::vector<std::string> names = builtin_scene_names();
    if (std::find(names.begin(), names.end(), scene_name) == names.end()) {
        std::string known;
        for (const std::string &name : names) known += (known.empty() ? "" : ", ") + name;
        throw Error("unknown scene '" + scene_name + "' (built-in scenes: " + known + ")");
    }
    const SceneDescription scene = make_grids_scene(settings.width, settings.height);

    AovSet aovs(settings.width, settings.height);
    const auto beauty = role_channels(aovs, Role::Beauty);
    const auto visibility = role_channels(aovs, Role::Visibility);
    const auto d1 = role_channels(aovs, Role::D1);
    const auto d2_min = role_channels(aovs, Role::D2Min);
    const auto d2_max = role_channels(aovs, Role::D2Max);
    const auto position = role_channels(aovs, Role::Position);
    const auto normal = role_channels(aovs, Role::Normal);
    const auto object_id = role_channels(aovs, Role::ObjectId);
    const auto spp = role_channels(aovs, Role::SamplesPerPixel);
    const auto pixel_size = role_channels(aovs, Role::PixelSize);
    const auto unshadowed = role_channels(aovs, Role::Unshadowed);
    write_light_attributes(scene.light, aovs);
    aovs.attributes[attr::kScene] = scene_name;
    aovs.attributes[attr::kSeed] = int(settings.seed);
    aovs.attributes[attr::kSpp] = settings.spp;

    const Renderer renderer(scene, settings);
    auto render_pixel = [&](int x, int y) {
        const PrimaryHit primary = renderer.trace_primary(x, y);
        visibility[0](x, y) = 1.0f;
        if (!primary.found) return;  // background: zeros, visibility 1, no samples
        ShadowStats stats;
        renderer.trace_shadows(primary, std::uint64_t(y) * settings.width + x, 0, std::uint32_t(settings.spp),
                               stats);
        const float v = stats.visibility();
        const std::array<float, 3> r{primary.unshadowed.x, primary.unshadowed.y, primary.unshadowed.z};
        const std::array<float, 3> p{primary.position.x, primary.position.y, primary.position.z};
        const std::array<float, 3> n{primary.normal.x, primary.normal.y, primary.normal.z};
        for (int c = 0; c < 3; ++c) {
            beauty[c](x, y) = r[c] * v;
            unshadowed[c](x, y) = r[c];
            position[c](x, y) = p[c];
            normal[c](x, y) = n[c];
        }
        visibility[0](x, y) = v;
        d1[0](x, y) = scene.light.plane_distance_m(primary.position);
        if (stats.occluded_any()) {
            d2_min[0](x, y) = stats.d2_min_m;
            d2_max[0](x, y) = stats.d2_max_m;
        }
        object_id[0](x, y) = float(primary.mesh->object_id);
        spp[0](x, y) = float(stats.taken);
        pixel_size[0](x, y) = primary.pixel_size_m;
    };

    tbb::task_arena arena(settings.threads == 0 ? tbb::task_arena::automatic : settings.threads);
    arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range2d<int>(0, settings.height, kTileSize, 0, settings.width, kTileSize),
                          [&](const tbb::blocked_range2d<int> &tile) {
                              for (int y = tile.rows().begin(); y != tile.rows().end(); ++y)
                                  for (int x = tile.cols().begin(); x != tile.cols().end(); ++x) render_pixel(x, y);
                          });
    });
    return aovs;
}

}  // namespace aaf::trace
