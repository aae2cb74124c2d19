#pragma once

#include <array>

#include "aaf/core/math/vec3d.h"

namespace aaf {

/// A convex planar polygon of at most kMaxVertices vertices, as seen from a
/// shading point: each vertex is the vector from that point to a corner,
/// in a frame whose z axis is the point's normal (units cancel).
struct LocalPolygon {
    static constexpr int kMaxVertices = 8;
    std::array<Vec3d, kMaxVertices> vertices{};
    int count = 0;

    /// Appends a vertex; throws aaf::Error beyond kMaxVertices.
    void add(Vec3d v);
};

/// The part of `polygon` with z >= 0 (Sutherland-Hodgman against the
/// shading point's tangent plane): a quad can become a pentagon, a polygon
/// entirely below becomes empty. Needs polygon.count < kMaxVertices.
LocalPolygon clip_to_upper_hemisphere(const LocalPolygon &polygon);

/// Signed edge integral (1 / 2 pi) sum_k theta_k n_k.z over the polygon's
/// edges, theta_k the angle between consecutive vertex directions and n_k
/// their unit cross product (Lambert's formula; ratio estimator Eq. 20 for a
/// Lambertian BRDF): the cosine-weighted solid angle over pi, its sign set by
/// the winding seen from the point. No clipping is done here.
/// Each edge term is computed as atan2(|a x b|, a . b) times (a x b).z / |a x b|
/// in double from the unnormalised vertices, which stays accurate where two
/// vertex directions are nearly identical (tiny or distant lights) or nearly
/// opposite (a point close to the light's plane); an exactly degenerate
/// edge (a x b = 0) contributes 0.
double polygon_edge_integral(const LocalPolygon &polygon);

/// The form factor of a one-sided emitter polygon from a shading point: the
/// integral of cos(theta) / pi over the solid angle of the polygon's part
/// above the horizon, in [0, 1]. A Lambertian surface of albedo rho lit by
/// the polygon with uniform radiance L reflects rho * L * form factor.
double polygon_form_factor(const LocalPolygon &polygon);

}  // namespace aaf

namespace aaf {

/// An orthonormal shading frame: z is the unit normal, x the tangent towards
/// the viewer (so that the view vector lies in the x-z plane, the frame of the
/// LTC table), y = z x x. With the viewer along the normal any tangent is used.
struct ShadingFrame {
    Vec3d x, y, z;

    /// Frame of unit normal `n` and unit direction to the viewer `wo`.
    static ShadingFrame from(Vec3d n, Vec3d wo);
    /// `v` in frame coordinates.
    Vec3d to_local(Vec3d v) const { return {dot(v, x), dot(v, y), dot(v, z)}; }
};

}  // namespace aaf
