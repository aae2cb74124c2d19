#pragma once

#include <cstdint>

#include "aaf/trace/shading/rect_light_shading.h"
#include "renderer.h"
#include "scene_description.h"

namespace aaf::trace {

/// One light's layers at one pixel (ratio estimator Eq. 20-22), per channel, W / (m^2 sr): the analytic U and
/// the means over the pixel's N samples of w R L V / p (S_N) and w R L / p (U_N).
struct RatioLayers {
    Vec3 analytic;
    Vec3 shadowed;
    Vec3 unshadowed;
};

/// The light of `light` as the ratio estimator integrates it: its rectangle
/// with uniform radiance intensity * colour / area (a light of that
/// radiance has intensity `intensity` along its normal, like the point-light
/// shading of r(x) at distance; its emission profile is not used).
RectLight ratio_light(const SceneLight &light);

/// Probability of drawing a sample from the GGX lobe rather than the light,
/// given the pixel's analytic U split by lobe (`u`) and whether the BRDF has a
/// GGX lobe towards `wo` (`glossy`): the specular share of U's luminance,
/// kept within [0.1, 0.9] so that both techniques cover their lobes (the
/// paper's rule, Sec. 4.3, with a clamp); 0 without a glossy lobe.
double glossy_sampling_probability(const UnshadowedLight &u, bool glossy);

/// U, S_N and U_N of light `light_index` at `primary` (found) from `samples`
/// samples, their shadow rays traced through `rays`, each drawn from the light (solid angle,
/// spherical_rectangle.h) or from the GGX lobe with glossy_sampling_probability(), the choice stratified over
/// the samples (a randomly shifted lattice over a hashed permutation of the sample index, so that each
/// technique's strata spread over the square), and weighted by the balance heuristic of the one-sample model:
/// R L / (q_light p_light + q_glossy p_glossy). S_N and U_N add the same values in the same order, so S_N ==
/// U_N bit for bit where no shadow ray is blocked. Random numbers depend only on (seed, pixel, light).
RatioLayers trace_ratio_layers(const RayQueries &rays, const SceneDescription &scene,
                               const PrimaryHit &primary, std::size_t light_index, int samples,
                               std::uint64_t seed, std::uint64_t pixel_index);

}  // namespace aaf::trace
