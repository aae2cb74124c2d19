#pragma once

#include "aaf/core/contract/light_plane.h"
#include "aaf/core/math/vec3d.h"

namespace aaf::trace {

/// Sampling of a rectangular light as seen from a shading point: uniform in
/// the solid angle it subtends (Urena, Fajardo, King 2013, "An area-preserving
/// parametrization for spherical rectangles"), or, where that map loses
/// precision, uniform over its area. Which one is used depends only on the
/// point and the light, so pdf() agrees with sample() for any direction
/// (MIS needs the density of directions other techniques produce). Double precision.
class SphericalRectangle {
  public:
    /// Solid angles below this (sr) fall back to area sampling: the map's
    /// angles then differ in the last digits only and its inverse is ill-conditioned.
    static constexpr double kMinSolidAngle_sr = 1e-5;
    /// Points closer to the light's plane than this fraction of its larger
    /// side fall back to area sampling (grazing: the spherical rectangle
    /// degenerates to a great-circle arc).
    static constexpr double kMinPlaneDistance = 1e-4;

    /// The rectangle of `light` seen from `p` (world metres).
    SphericalRectangle(const LightPlane &light, Vec3d p);

    /// Whether `p` lies on the emitting side at a positive distance: otherwise
    /// no direction reaches the light's front and sample()/pdf() are not to be used.
    bool visible() const { return visible_; }
    bool uses_solid_angle() const { return solid_angle_mode_; }
    /// The subtended solid angle in sr (with area sampling, as the map computed it).
    double solid_angle_sr() const { return solid_angle_sr_; }

    /// The light point for uniforms u1, u2 in [0, 1) (world metres).
    Vec3d sample(double u1, double u2) const;
    /// Density over solid angle at `p` of sample() producing the light point
    /// `y` (on the rectangle): 1 / solid angle, or r^2 / (area cos_light).
    double pdf(Vec3d y) const;
    /// The light point along unit `direction` from `p`, if the ray meets the
    /// rectangle's front; false otherwise.
    bool intersect(Vec3d direction, Vec3d &y) const;

  private:
    Vec3d p_, corner_, ex_, ey_, x_, y_, z_, normal_;
    double width_ = 0, height_ = 0;
    double x0_ = 0, y0_ = 0, z0_ = 0, x1_ = 0, y1_ = 0;
    double b0_ = 0, b1_ = 0, k_ = 0;
    double solid_angle_sr_ = 0;
    bool visible_ = false, solid_angle_mode_ = false;
};

}  // namespace aaf::trace
