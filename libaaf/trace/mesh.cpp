#include <algorithm>
#include <cmath>

#include "scene_description.h"

namespace aaf::trace {

void Mesh::add_quad(Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
    const auto base = std::uint32_t(positions.size());
    positions.insert(positions.end(), {a, b, c, d});
    indices.insert(indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

void Mesh::add_box(Vec3 lo, Vec3 hi, float angle_rad) {
    const float c = std::cos(angle_rad), s = std::sin(angle_rad);
    auto corner = [&](int i) {
        const Vec3 p{(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z};
        return Vec3{c * p.x + s * p.z, p.y, -s * p.x + c * p.z};
    };
    // Corner i has x from bit 0, y from bit 1, z from bit 2.
    add_quad(corner(0), corner(1), corner(3), corner(2));  // z = lo
    add_quad(corner(4), corner(6), corner(7), corner(5));  // z = hi
    add_quad(corner(0), corner(2), corner(6), corner(4));  // x = lo
    add_quad(corner(1), corner(5), corner(7), corner(3));  // x = hi
    add_quad(corner(0), corner(4), corner(5), corner(1));  // y = lo
    add_quad(corner(2), corner(3), corner(7), corner(6));  // y = hi
}

Mesh ground_plane(float half_extent_m, int object_id, Vec3 albedo) {
    Mesh ground;
    ground.object_id = object_id;
    ground.albedo = albedo;
    const float h = half_extent_m;
    ground.add_quad({-h, 0, -h}, {-h, 0, h}, {h, 0, h}, {h, 0, -h});
    return ground;
}

void Mesh::add_sphere(Vec3 center, float radius_m, int segments) {
    constexpr float kPi = 3.14159265358979f;
    const int rings = segments / 2;
    const auto base = std::uint32_t(positions.size());
    for (int j = 0; j <= rings; ++j) {
        const float theta = kPi * float(j) / float(rings);
        for (int i = 0; i <= segments; ++i) {
            const float phi = 2 * kPi * float(i) / float(segments);
            positions.push_back(center + Vec3{std::sin(theta) * std::cos(phi), std::cos(theta),
                                              std::sin(theta) * std::sin(phi)} *
                                             radius_m);
        }
    }
    const auto stride = std::uint32_t(segments + 1);
    for (int j = 0; j < rings; ++j)
        for (int i = 0; i < segments; ++i) {
            const std::uint32_t a = base + std::uint32_t(j) * stride + std::uint32_t(i);
            // Poles collapse one triangle of each quad; skip the degenerate one.
            if (j != 0) indices.insert(indices.end(), {a, a + 1, a + stride});
            if (j != rings - 1) indices.insert(indices.end(), {a + 1, a + stride + 1, a + stride});
        }
}

void Mesh::add_tube(const std::vector<Vec3> &centre, const std::vector<float> &radius_m, int sides) {
    constexpr float kPi = 3.14159265358979f;
    const auto base = std::uint32_t(positions.size());
    const std::size_t count = centre.size();
    for (std::size_t k = 0; k < count; ++k) {
        const Vec3 tangent = normalize(centre[std::min(k + 1, count - 1)] - centre[k == 0 ? 0 : k - 1]);
        const Vec3 helper = std::fabs(tangent.y) < 0.9f ? Vec3{0, 1, 0} : Vec3{1, 0, 0};
        const Vec3 side = normalize(cross(tangent, helper)), other = cross(tangent, side);
        for (int i = 0; i < sides; ++i) {
            const float angle = 2 * kPi * float(i) / float(sides);
            positions.push_back(centre[k] + (side * std::cos(angle) + other * std::sin(angle)) * radius_m[k]);
        }
    }
    const auto ring = std::uint32_t(sides);
    for (std::size_t k = 0; k + 1 < count; ++k)
        for (std::uint32_t i = 0; i < ring; ++i) {
            const std::uint32_t a = base + std::uint32_t(k) * ring + i,
                                b = base + std::uint32_t(k) * ring + (i + 1) % ring;
            indices.insert(indices.end(), {a, b, b + ring, a, b + ring, a + ring});
        }
}

}  // namespace aaf::trace
