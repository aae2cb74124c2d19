#include <cmath>

#include "scene_description.h"

namespace aaf::trace {

namespace {

constexpr float kPi = 3.14159265358979f;

}  // namespace

Transform Transform::from(Vec3 scale, Vec3 rotate_deg, Vec3 translate) {
    const float to_rad = kPi / 180.0f;
    const float cx = std::cos(rotate_deg.x * to_rad), sx = std::sin(rotate_deg.x * to_rad);
    const float cy = std::cos(rotate_deg.y * to_rad), sy = std::sin(rotate_deg.y * to_rad);
    const float cz = std::cos(rotate_deg.z * to_rad), sz = std::sin(rotate_deg.z * to_rad);
    // R = Rz * Ry * Rx (x applied first), right-handed.
    const float rx[3][3] = {{1, 0, 0}, {0, cx, -sx}, {0, sx, cx}};
    const float ry[3][3] = {{cy, 0, sy}, {0, 1, 0}, {-sy, 0, cy}};
    const float rz[3][3] = {{cz, -sz, 0}, {sz, cz, 0}, {0, 0, 1}};
    float ryx[3][3] = {};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k) ryx[i][j] += ry[i][k] * rx[k][j];
    Transform t;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            float r = 0;
            for (int k = 0; k < 3; ++k) r += rz[i][k] * ryx[k][j];
            t.m[i][j] = r * scale[j];
        }
    t.translation = translate;
    return t;
}

void Mesh::add_quad(Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
    const auto base = std::uint32_t(positions.size());
    positions.insert(positions.end(), {a, b, c, d});
    indices.insert(indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

void Mesh::add_box(Vec3 lo, Vec3 hi, const Transform &to_world) {
    // Corner i has x from bit 0, y from bit 1, z from bit 2.
    auto corner = [&](int i) {
        return to_world.apply({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
    };
    add_quad(corner(0), corner(1), corner(3), corner(2));  // z = lo
    add_quad(corner(4), corner(6), corner(7), corner(5));  // z = hi
    add_quad(corner(0), corner(2), corner(6), corner(4));  // x = lo
    add_quad(corner(1), corner(5), corner(7), corner(3));  // x = hi
    add_quad(corner(0), corner(4), corner(5), corner(1));  // y = lo
    add_quad(corner(2), corner(3), corner(7), corner(6));  // y = hi
}

void Mesh::add_sphere(Vec3 center, float radius_m, int segments, const Transform &to_world) {
    const int rings = segments / 2;
    const auto base = std::uint32_t(positions.size());
    for (int j = 0; j <= rings; ++j) {
        const float theta = kPi * float(j) / float(rings);
        for (int i = 0; i <= segments; ++i) {
            const float phi = 2 * kPi * float(i) / float(segments);
            const Vec3 unit{std::sin(theta) * std::cos(phi), std::cos(theta),
                            std::sin(theta) * std::sin(phi)};
            positions.push_back(to_world.apply(center + unit * radius_m));
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

void Mesh::add_cylinder(float radius_m, float height_m, int segments, const Transform &to_world) {
    const auto base = std::uint32_t(positions.size());
    for (int i = 0; i < segments; ++i) {
        const float phi = 2 * kPi * float(i) / float(segments);
        const float x = radius_m * std::cos(phi), z = radius_m * std::sin(phi);
        positions.push_back(to_world.apply({x, 0, z}));
        positions.push_back(to_world.apply({x, height_m, z}));
    }
    const auto bottom = std::uint32_t(positions.size());
    positions.push_back(to_world.apply({0, 0, 0}));
    positions.push_back(to_world.apply({0, height_m, 0}));
    const auto n = std::uint32_t(segments);
    for (std::uint32_t i = 0; i < n; ++i) {
        const std::uint32_t a = base + 2 * i, b = base + 2 * ((i + 1) % n);
        indices.insert(indices.end(), {a, a + 1, b + 1, a, b + 1, b});  // side
        indices.insert(indices.end(), {bottom, a, b});                  // bottom cap
        indices.insert(indices.end(), {bottom + 1, b + 1, a + 1});      // top cap
    }
}

}  // namespace aaf::trace
