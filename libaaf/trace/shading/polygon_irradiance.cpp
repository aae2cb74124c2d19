#include "aaf/trace/shading/polygon_irradiance.h"

#include <cmath>

#include "aaf/core/util/error.h"

namespace aaf {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// theta * n.z for the edge a -> b (ratio estimator Eq. 20 with Lambert's
/// edge formula). atan2 of the unnormalised sine and cosine is scale-free and
/// well conditioned at both ends of [0, pi], where acos of a dot product is not.
double edge_term(Vec3d a, Vec3d b) {
    const Vec3d c = cross(a, b);
    const double sine = length(c);  // |a| |b| sin(theta)
    if (!(sine > 0)) return 0;      // a and b on one line through the point: no area
    const double theta = std::atan2(sine, dot(a, b));
    return theta * (c.z / sine);
}

}  // namespace

void LocalPolygon::add(Vec3d v) {
    if (count >= kMaxVertices) throw Error("internal: a local polygon holds at most 8 vertices");
    vertices[std::size_t(count++)] = v;
}

LocalPolygon clip_to_upper_hemisphere(const LocalPolygon &polygon) {
    LocalPolygon clipped;
    for (int k = 0; k < polygon.count; ++k) {
        const Vec3d a = polygon.vertices[std::size_t(k)];
        const Vec3d b = polygon.vertices[std::size_t((k + 1) % polygon.count)];
        const bool a_above = a.z >= 0, b_above = b.z >= 0;
        if (a_above) clipped.add(a);
        if (a_above != b_above) {
            // The edge crosses the horizon: its point with z = 0.
            const double t = a.z / (a.z - b.z);
            Vec3d crossing = a + (b - a) * t;
            crossing.z = 0;
            clipped.add(crossing);
        }
    }
    return clipped;
}

double polygon_edge_integral(const LocalPolygon &polygon) {
    double sum = 0;
    for (int k = 0; k < polygon.count; ++k)
        sum += edge_term(polygon.vertices[std::size_t(k)],
                         polygon.vertices[std::size_t((k + 1) % polygon.count)]);
    return sum / (2 * kPi);
}

double polygon_form_factor(const LocalPolygon &polygon) {
    const LocalPolygon above = clip_to_upper_hemisphere(polygon);
    if (above.count < 3) return 0;
    // The winding seen from the point decides the sign; a one-sided emitter
    // facing away is the caller's test (it has the emitter's normal).
    return std::fabs(polygon_edge_integral(above));
}

}  // namespace aaf

namespace aaf {

ShadingFrame ShadingFrame::from(Vec3d n, Vec3d wo) {
    ShadingFrame frame;
    frame.z = n;
    Vec3d tangent = wo - n * dot(n, wo);
    if (!(length(tangent) > 1e-9))
        tangent = std::fabs(n.x) < 0.9 ? cross(n, Vec3d{1, 0, 0}) : cross(n, Vec3d{0, 1, 0});
    frame.x = normalize(tangent);
    frame.y = cross(frame.z, frame.x);
    return frame;
}

}  // namespace aaf
