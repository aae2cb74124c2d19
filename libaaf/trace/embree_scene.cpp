#include "embree_scene.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <string>

#include "aaf/core/math/vec3d.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/instruction_set.h"

namespace aaf::trace {

namespace {

const char *embree_error_name(RTCError code) {
    switch (code) {
        case RTC_ERROR_NONE:
            return "no error";
        case RTC_ERROR_INVALID_ARGUMENT:
            return "invalid argument";
        case RTC_ERROR_INVALID_OPERATION:
            return "invalid operation";
        case RTC_ERROR_OUT_OF_MEMORY:
            return "out of memory";
        case RTC_ERROR_UNSUPPORTED_CPU:
            return "unsupported CPU";
        case RTC_ERROR_CANCELLED:
            return "cancelled";
        default:
            return "unknown error";
    }
}

void check_device(RTCDevice device, const char *what) {
    const RTCError code = rtcGetDeviceError(device);
    if (code != RTC_ERROR_NONE) throw Error(std::string("Embree: ") + what + ": " + embree_error_name(code));
}

/// rtcNewDevice's configuration for `set`.
const char *embree_device_config(InstructionSet set) {
    switch (set) {
        case InstructionSet::Sse42:
            return "isa=sse4.2";
        case InstructionSet::Avx2:
            return "isa=avx2";
        case InstructionSet::Avx512:
            return "isa=avx512";
        case InstructionSet::Native:
            break;
    }
    return nullptr;  // Embree's choice: the fastest kernels this CPU runs
}

}  // namespace

EmbreeScene::EmbreeScene(const SceneDescription &description, bool high_quality, bool robust, bool packets)
    : packets_(packets) {
    device_ = rtcNewDevice(embree_device_config(instruction_set()));
    if (!device_) throw Error("Embree: cannot create a device");
    try {
        scene_ = rtcNewScene(device_);
        rtcSetSceneFlags(scene_, robust ? RTC_SCENE_FLAG_ROBUST : RTC_SCENE_FLAG_NONE);
        rtcSetSceneBuildQuality(scene_, high_quality ? RTC_BUILD_QUALITY_HIGH : RTC_BUILD_QUALITY_MEDIUM);
        for (const Mesh &mesh : description.meshes) {
            RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
            auto *vertices = static_cast<float *>(
                rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                        3 * sizeof(float), mesh.positions.size()));
            auto *indices = static_cast<unsigned *>(
                rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                        3 * sizeof(unsigned), mesh.indices.size() / 3));
            check_device(device_, "allocating geometry buffers");
            for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
                vertices[3 * i + 0] = mesh.positions[i].x;
                vertices[3 * i + 1] = mesh.positions[i].y;
                vertices[3 * i + 2] = mesh.positions[i].z;
            }
            std::memcpy(indices, mesh.indices.data(), mesh.indices.size() * sizeof(unsigned));
            triangles_.push_back({vertices, indices});  // the scene keeps the buffers alive
            rtcSetGeometryBuildQuality(geometry,
                                       high_quality ? RTC_BUILD_QUALITY_HIGH : RTC_BUILD_QUALITY_MEDIUM);
            rtcCommitGeometry(geometry);
            rtcAttachGeometry(scene_, geometry);  // geometry ids follow mesh order
            rtcReleaseGeometry(geometry);
        }
        rtcCommitScene(scene_);
        check_device(device_, "building the BVH");
    } catch (...) {
        if (scene_) rtcReleaseScene(scene_);
        rtcReleaseDevice(device_);
        throw;
    }
}

EmbreeScene::~EmbreeScene() {
    rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
}

Hit EmbreeScene::intersect(Vec3 origin, Vec3 direction, float t_near, float t_far) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit query;
    query.ray.org_x = origin.x;
    query.ray.org_y = origin.y;
    query.ray.org_z = origin.z;
    query.ray.dir_x = direction.x;
    query.ray.dir_y = direction.y;
    query.ray.dir_z = direction.z;
    query.ray.tnear = t_near;
    query.ray.tfar = t_far;
    query.ray.time = 0;
    query.ray.mask = std::numeric_limits<unsigned>::max();
    query.ray.id = 0;
    query.ray.flags = 0;
    query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    query.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_, &context, &query);

    Hit hit;
    if (query.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
    hit.found = true;
    hit.mesh_index = query.hit.geomID;
    // Embree found the triangle; where the ray meets it is computed here, the
    // same on every CPU (Embree's kernels differ in the last bits: its
    // reciprocal estimates differ between instruction sets and vendors).
    const MeshBuffers &mesh = triangles_[query.hit.geomID];
    const unsigned *corner = mesh.indices + 3 * std::size_t(query.hit.primID);
    const auto vertex = [&](unsigned index) {
        const float *p = mesh.vertices + 3 * std::size_t(index);
        return Vec3d(p[0], p[1], p[2]);
    };
    const Vec3d v0 = vertex(corner[0]), edge1 = vertex(corner[1]) - v0, edge2 = vertex(corner[2]) - v0;
    // The plane's distance t = ((v0 - o) . n) / (d . n), n = e1 x e2 (the
    // normal as Embree's), in double precision.
    const Vec3d normal = cross(edge1, edge2);
    const Vec3d d(direction.x, direction.y, direction.z);
    const double denominator = dot(d, normal);
    const double t = denominator != 0 ? dot(v0 - Vec3d(origin.x, origin.y, origin.z), normal) / denominator
                                      : double(query.ray.tfar);
    // Within the interval searched, where rounding at its ends could leave it.
    hit.distance = float(std::clamp(t, double(t_near), double(t_far)));
    hit.geometric_normal = {float(normal.x), float(normal.y), float(normal.z)};
    return hit;
}

void EmbreeScene::primary_hits(const Camera &camera, int y, int x_begin, int x_end, Hit *hits) const {
    for (int x = x_begin; x < x_end; ++x)
        hits[x - x_begin] = intersect(camera.eye, camera.ray_direction(x + 0.5f, y + 0.5f), 0.0f,
                                      std::numeric_limits<float>::infinity());
}

void EmbreeScene::occluded(Vec3 origin, const Vec3 *directions, int count, float t_near, float t_far,
                           bool *blocked) const {
    // A lone ray (a shading query) goes as one: a packet of one lane costs more.
    if (!packets_ || count == 1) {
        for (int k = 0; k < count; ++k) blocked[k] = occluded1(origin, directions[k], t_near, t_far);
        return;
    }
    for (int first = 0; first < count; first += kPacketSize)
        occluded_packet(origin, directions + first, std::min(kPacketSize, count - first), t_near, t_far,
                        blocked + first);
}

void EmbreeScene::occluded_packet(Vec3 origin, const Vec3 *directions, int count, float t_near, float t_far,
                                  bool *blocked) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    // One pixel's shadow rays share their origin and aim at one light.
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    alignas(64) int valid[kPacketSize];
    alignas(64) RTCRay16 packet;
    for (int k = 0; k < kPacketSize; ++k) {
        const bool active = k < count;
        const Vec3 direction = directions[active ? k : 0];
        valid[k] = active ? -1 : 0;
        packet.org_x[k] = origin.x;
        packet.org_y[k] = origin.y;
        packet.org_z[k] = origin.z;
        packet.dir_x[k] = direction.x;
        packet.dir_y[k] = direction.y;
        packet.dir_z[k] = direction.z;
        packet.tnear[k] = t_near;
        packet.tfar[k] = t_far;
        packet.time[k] = 0;
        packet.mask[k] = std::numeric_limits<unsigned>::max();
        packet.id[k] = 0;
        packet.flags[k] = 0;
    }
    rtcOccluded16(valid, scene_, &context, &packet);
    for (int k = 0; k < count; ++k) blocked[k] = packet.tfar[k] < 0;  // -inf on a hit
}

}  // namespace aaf::trace
