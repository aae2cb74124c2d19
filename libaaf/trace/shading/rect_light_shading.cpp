#include "aaf/trace/shading/rect_light_shading.h"

#include "aaf/trace/shading/ltc_ggx.h"
#include "aaf/trace/shading/polygon_irradiance.h"

namespace aaf {

namespace {

Vec3d to_double(Vec3 v) {
    return {double(v.x), double(v.y), double(v.z)};
}

}  // namespace

UnshadowedLight rect_light_unshadowed(const RectLight &light, Vec3 p, Vec3 n, Vec3 wo,
                                      const SurfaceReflectance &surface) {
    UnshadowedLight result;
    const LightPlane &plane = light.plane;
    const Vec3d centre = to_double(plane.center) - to_double(p);
    // One-sided emitter: nothing reaches a point behind (or in) its plane.
    if (!(dot(to_double(plane.normal), centre) < 0)) return result;
    const Vec3d half_u = to_double(plane.axis_u) * (0.5 * plane.width_m);
    const Vec3d half_v = to_double(plane.axis_v) * (0.5 * plane.height_m);
    const Vec3d corners[4] = {centre - half_u - half_v, centre + half_u - half_v, centre + half_u + half_v,
                              centre - half_u + half_v};
    const ShadingFrame frame = ShadingFrame::from(normalize(to_double(n)), normalize(to_double(wo)));
    LocalPolygon polygon;
    for (const Vec3d &corner : corners) polygon.add(frame.to_local(corner));

    // ratio estimator Eq. 20 for the Lambertian lobe: (rho / pi) L times the
    // clipped cosine-weighted solid angle, i.e. rho L times the form factor.
    const double form_factor = polygon_form_factor(polygon);
    for (int c = 0; c < 3; ++c) {
        const double value = double(surface.albedo[c]) * double(light.radiance[c]) * form_factor;
        (c == 0 ? result.diffuse.x : c == 1 ? result.diffuse.y : result.diffuse.z) = float(value);
    }
    if (!(surface.specular.x > 0 || surface.specular.y > 0 || surface.specular.z > 0)) return result;
    const double cos_view = dot(normalize(to_double(wo)), frame.z);
    // LTC Eq. 10 with Schlick's Fresnel split into the table's two integrals.
    const ltc_ggx::PolygonIntegral lobe = ltc_ggx::integrate(polygon, double(surface.roughness), cos_view);
    for (int c = 0; c < 3; ++c) {
        const double f0 = double(surface.specular[c]);
        const double value =
            (f0 * lobe.magnitude_term + (1 - f0) * lobe.fresnel_term) * double(light.radiance[c]);
        (c == 0 ? result.specular.x : c == 1 ? result.specular.y : result.specular.z) = float(value);
    }
    return result;
}

}  // namespace aaf
