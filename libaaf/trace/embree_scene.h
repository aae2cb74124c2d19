#pragma once

#include <embree3/rtcore.h>

#include <limits>
#include <vector>

#include "ray_queries.h"
#include "scene_description.h"

namespace aaf::trace {

/// The scene's meshes in an Embree 3 BVH (owns the device and the scene):
/// the CPU's RayQueries. Thread-safe for concurrent queries once built.
class EmbreeScene final : public RayQueries {
  public:
    /// Builds with RTC_SCENE_FLAG_ROBUST (no leaks between adjacent
    /// triangles) unless `robust` is false (for benchmarks only);
    /// `high_quality` selects RTC_BUILD_QUALITY_HIGH (a slower build that pays
    /// off over the many rays of a reference). `packets`: occluded() batches
    /// go to Embree as rtcOccluded16 packets rather than one rtcOccluded1 a
    /// ray (the same answers; only the speed differs).
    EmbreeScene(const SceneDescription &scene, bool high_quality, bool robust = true, bool packets = false);
    ~EmbreeScene();
    EmbreeScene(const EmbreeScene &) = delete;
    EmbreeScene &operator=(const EmbreeScene &) = delete;

    // RayQueries
    void primary_hits(const Camera &camera, int y, int x_begin, int x_end, Hit *hits) const override;
    using RayQueries::occluded;
    void occluded(Vec3 origin, const Vec3 *directions, int count, float t_near, float t_far,
                  bool *blocked) const override;
    Hit closest_hit(Vec3 origin, Vec3 direction, float t_near, float t_far) const override {
        return intersect(origin, direction, t_near, t_far);
    }

    /// Closest hit of origin + t direction for t in [t_near, t_far] (rtcIntersect1).
    Hit intersect(Vec3 origin, Vec3 direction, float t_near, float t_far) const;
    /// Whether anything lies on origin + t direction for t in [t_near, t_far]
    /// (rtcOccluded1: stops at the first hit found).
    bool occluded1(Vec3 origin, Vec3 direction, float t_near, float t_far) const;

    /// Packet size of occluded_packet().
    static constexpr int kPacketSize = 16;
    /// occluded() of `count` <= kPacketSize rays from one origin, origin +
    /// t directions[k] for t in [t_near, t_far], as one rtcOccluded16 packet:
    /// blocked[k] for k < count.
    void occluded_packet(Vec3 origin, const Vec3 *directions, int count, float t_near, float t_far,
                         bool *blocked) const;

    RTCScene handle() const { return scene_; }

  private:
    /// A mesh's vertex and index buffers, as given to Embree.
    struct MeshBuffers {
        const float *vertices;    ///< x, y, z per vertex
        const unsigned *indices;  ///< three per triangle
    };

    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
    std::vector<MeshBuffers> triangles_;  ///< by geometry id
    bool packets_ = false;                ///< occluded() batches as rtcOccluded16 packets
};

// Inline: it runs once per shadow ray.
inline bool EmbreeScene::occluded1(Vec3 origin, Vec3 direction, float t_near, float t_far) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray;
    ray.org_x = origin.x;
    ray.org_y = origin.y;
    ray.org_z = origin.z;
    ray.dir_x = direction.x;
    ray.dir_y = direction.y;
    ray.dir_z = direction.z;
    ray.tnear = t_near;
    ray.tfar = t_far;
    ray.time = 0;
    ray.mask = std::numeric_limits<unsigned>::max();
    ray.id = 0;
    ray.flags = 0;
    rtcOccluded1(scene_, &context, &ray);
    return ray.tfar < 0;  // Embree sets tfar to -inf on a hit
}

}  // namespace aaf::trace
