// What bench_trace.cpp and bench_trace_end_to_end.cpp share: the shadow
// rays a render traces, generated as Renderer::trace_shadows generates them,
// and the raw Embree loops over them.
#pragma once

#include <embree3/rtcore.h>
#include <pmmintrin.h>  // flush-to-zero and denormals-are-zero

#include <array>
#include <chrono>
#include <cstdint>
#include <limits>
#include <vector>

#include "aaf/trace/render.h"
#include "light_sampler.h"
#include "random.h"
#include "renderer.h"
#include "stratified_grid.h"

namespace aaf::bench {

using namespace aaf::trace;

struct Ray {
    Vec3 origin, direction;
    float t_far;
};

/// Calls `emit` with every shadow ray the sample loop of
/// Renderer::trace_shadows traces for `primary` (pixel index `pixel`) in
/// pass 0 of `Spp` samples, in the same order.
template <std::uint32_t Spp, typename Emit>
void for_each_pixel_shadow_ray(const SceneDescription &scene, const LightSampler &sampler, std::uint64_t seed,
                               const PrimaryHit &primary, std::uint64_t pixel, const Emit &emit) {
    if (!primary.found) return;
    PixelRng rng(seed, pixel, 0);
    const std::uint32_t key = rng.next_u32();
    const StratifiedGrid strata(Spp);
    const Vec3 origin = offset_ray_origin(primary.position, primary.normal);
    // As the tracer: the batch's unit points, then the warp over the batch (the same bits
    // as LightSampler::point one at a time), then the rays.
    std::array<float, Spp> s, t, u_m, v_m;
    for (std::uint32_t i = 0; i < Spp; ++i) {
        float u1, u2;
        rng.next_float2(u1, u2);
        const UnitPoint p = strata.point(i, key, u1, u2);
        s[i] = p.s;
        t[i] = p.t;
    }
    sampler.warp(s.data(), t.data(), Spp, u_m.data(), v_m.data());
    for (std::uint32_t i = 0; i < Spp; ++i) {
        const Vec3 target = scene.key_light().point_at(u_m[i], v_m[i]);
        if (dot(primary.normal, target - primary.position) <= 0) continue;  // not traced
        emit(Ray{origin, target - origin, 1.0f - 1e-4f});
    }
}

inline double seconds(const std::chrono::steady_clock::time_point &start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

inline RTCRay to_rtc(const Ray &ray) {
    RTCRay r;
    r.org_x = ray.origin.x;
    r.org_y = ray.origin.y;
    r.org_z = ray.origin.z;
    r.dir_x = ray.direction.x;
    r.dir_y = ray.direction.y;
    r.dir_z = ray.direction.z;
    r.tnear = 0;
    r.tfar = ray.t_far;
    r.time = 0;
    r.mask = std::numeric_limits<unsigned>::max();
    r.id = 0;
    r.flags = 0;
    return r;
}

inline std::size_t run_occluded1(RTCScene scene, const std::vector<Ray> &rays) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    std::size_t blocked = 0;
    for (const Ray &ray : rays) {
        RTCRay r = to_rtc(ray);
        rtcOccluded1(scene, &context, &r);
        blocked += r.tfar < 0;
    }
    return blocked;
}

inline std::size_t run_intersect1(RTCScene scene, const std::vector<Ray> &rays) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    std::size_t hits = 0;
    for (const Ray &ray : rays) {
        RTCRayHit query;
        query.ray = to_rtc(ray);
        query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        query.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene, &context, &query);
        hits += query.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    }
    return hits;
}

/// Loads rays [start, start + N) (fewer at the end: masked off) into a packet.
inline void set_flush_to_zero(bool on) {
    _MM_SET_FLUSH_ZERO_MODE(on ? _MM_FLUSH_ZERO_ON : _MM_FLUSH_ZERO_OFF);
    _MM_SET_DENORMALS_ZERO_MODE(on ? _MM_DENORMALS_ZERO_ON : _MM_DENORMALS_ZERO_OFF);
}

}  // namespace aaf::bench
