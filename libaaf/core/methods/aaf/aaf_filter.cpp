#include "aaf/core/methods/aaf/aaf_filter.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "aaf/core/kernels/gather.h"
#include "aaf/core/kernels/light_bandlimit.h"
#include "aaf/core/methods/aaf/aaf_bandlimits.h"
#include "aaf/core/methods/aaf/aaf_guide_rows.h"
#include "aaf/core/methods/aaf/occluder_fill.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/parallel.h"
#include "aaf/core/util/plane_rows.h"

namespace aaf {

namespace {

/// Taps stop at 3 beta, where the Gaussian weight has fallen to exp(-4.5).
constexpr float kCutoffSigmas = 3.0f;

void check_size(ConstPlaneView view, int width, int height, const char *what) {
    if (!view.valid() || view.width != width || view.height != height)
        throw Error(std::string("AAF input '") + what + "' is missing or has another size");
}

void check_inputs(const AafInputs &in, const LightPlane &light, const AafParams &params) {
    params.validate();
    light.validate();
    const int width = in.visibility.width, height = in.visibility.height;
    if (width <= 0 || height <= 0) throw Error("AAF input 'visibility' is missing or empty");
    check_size(in.d1, width, height, "d1");
    check_size(in.d2_min, width, height, "d2min");
    check_size(in.d2_max, width, height, "d2max");
    for (int c = 0; c < 3; ++c) {
        check_size(in.position[c], width, height, "position");
        check_size(in.normal[c], width, height, "normal");
    }
    check_size(in.object_id, width, height, "object_id");
    check_size(in.pixel_size, width, height, "pixel_size");
    if (params.mu_from_spp || (!params.fixed_mu && in.spp.valid())) check_size(in.spp, width, height, "spp");
}

/// What every pixel's guide row shares: the light's frame and variances, the
/// band-limit, the parameters, and which optional guide planes are written.
detail::AafGuideConstants guide_constants(const AafInputs &in, const LightPlane &light,
                                          const AafParams &params) {
    const LightBandlimitAxes bandlimit_sigma_m = aaf_light_sigmas_m(light, params);
    detail::AafGuideConstants constants;
    for (int a = 0; a < 3; ++a) {
        constants.center[a] = light.center[a];
        constants.axis_u[a] = light.axis_u[a];
        constants.axis_v[a] = light.axis_v[a];
        constants.light_normal[a] = light.normal[a];
    }
    constants.variance_u_m2 = light.variance_u_m2();
    constants.variance_v_m2 = light.variance_v_m2();
    constants.sigma_u_m = bandlimit_sigma_m.u_m;
    constants.sigma_v_m = bandlimit_sigma_m.v_m;
    constants.mu = params.mu;
    constants.k = params.k;
    constants.alpha = params.alpha;
    constants.fixed_beta_m = params.fixed_beta_m;
    constants.max_radius_px = float(params.max_radius_px);
    constants.cutoff_sigmas = kCutoffSigmas;
    constants.projected_pixel = params.projected_pixel;
    constants.along_light = params.light_distance != AafLightDistance::OrthogonalProjection;
    constants.guarded = params.light_distance == AafLightDistance::Guarded;
    // One band-limit per light axis: the Gaussian is anisotropic in the light's plane.
    constants.anisotropic = bandlimit_sigma_m.u_m != bandlimit_sigma_m.v_m;
    // AAF Sec. 5.2: the filter follows the samples actually taken.
    constants.per_pixel_mu = !params.fixed_mu && in.spp.valid();
    return constants;
}

}  // namespace

GatherGuides aaf_gather_guides(const AafInputs &in, const LightPlane &light, const AafParams &params,
                               PlaneView beta_m) {
    check_inputs(in, light, params);
    if (beta_m.valid() && (beta_m.width != in.visibility.width || beta_m.height != in.visibility.height))
        throw Error("AAF output 'beta' has another size");
    // AAF Sec. 6: unoccluded pixels take the occluder distances of their neighbours.
    // Filled before the guides exist, so the search's scratch planes never coexist with them.
    const FilledOccluders occluders =
        fill_occluder_distances(in.d2_min, in.d2_max, in.object_id, params.fill_radius_px);
    // Sized without zero-filling: the guide rows below write every pixel of every plane.
    GatherGuides guides;
    guides.allocate(in.visibility.width, in.visibility.height);
    const std::size_t count = std::size_t(guides.width) * std::size_t(guides.height);
    const detail::AafGuideConstants constants = guide_constants(in, light, params);
    const bool anisotropic = constants.anisotropic, along_light = constants.along_light;
    if (anisotropic) guides.inv_two_sigma_sq_v.resize(count);
    if (along_light)
        for (FramePlane<float> *plane :
             {&guides.coord_n_m, &guides.shear_u, &guides.shear_v, &guides.inv_two_sigma_sq_n})
            plane->resize(count);

    // One pass over the inputs, row by row, neighbouring pixels in SIMD
    // lanes (aaf_guide_rows.h): coordinates, shear, normals, AAF Eq. 13's
    // beta (bisecting mu per pixel with the spp input) and the reach.
    parallel_for_rows(guides.height, [&](int y) {
        std::vector<float> buffers[11];
        detail::AafGuideRowInputs row_in;
        for (int a = 0; a < 3; ++a) {
            row_in.position[a] = contiguous_row(in.position[std::size_t(a)], y, buffers[a]);
            row_in.normal[a] = contiguous_row(in.normal[std::size_t(a)], y, buffers[3 + a]);
        }
        row_in.object_id = contiguous_row(in.object_id, y, buffers[6]);
        row_in.d1_m = contiguous_row(in.d1, y, buffers[7]);
        row_in.pixel_size_m = contiguous_row(in.pixel_size, y, buffers[8]);
        if (constants.per_pixel_mu) row_in.spp = contiguous_row(in.spp, y, buffers[9]);
        const std::size_t row = guides.index(0, y);
        row_in.d2_min_m = occluders.d2_min_m.data() + row;
        row_in.d2_max_m = occluders.d2_max_m.data() + row;
        detail::AafGuideRowOutputs row_out;
        row_out.coord_u_m = guides.coord_u_m.data() + row;
        row_out.coord_v_m = guides.coord_v_m.data() + row;
        row_out.normal[0] = guides.normal_x.data() + row;
        row_out.normal[1] = guides.normal_y.data() + row;
        row_out.normal[2] = guides.normal_z.data() + row;
        row_out.object_id = guides.object_id.data() + row;
        row_out.inv_two_sigma_sq = guides.inv_two_sigma_sq.data() + row;
        if (anisotropic) row_out.inv_two_sigma_sq_v = guides.inv_two_sigma_sq_v.data() + row;
        if (along_light) {
            row_out.coord_n_m = guides.coord_n_m.data() + row;
            row_out.shear_u = guides.shear_u.data() + row;
            row_out.shear_v = guides.shear_v.data() + row;
            row_out.inv_two_sigma_sq_n = guides.inv_two_sigma_sq_n.data() + row;
        }
        // Every pixel's beta is written (straight into the output where its pixels are adjacent).
        const bool beta_in_place = beta_m.valid() && beta_m.pixel_stride == 1;
        if (beta_m.valid()) {
            buffers[10].resize(beta_in_place ? 0 : std::size_t(guides.width));
            row_out.beta_m = beta_in_place ? &beta_m(0, y) : buffers[10].data();
        }
        row_out.radius_px = guides.radius_px.data() + row;
        detail::aaf_guide_row(constants, row_in, row_out, guides.width);
        if (beta_m.valid() && !beta_in_place)
            for (int x = 0; x < guides.width; ++x) beta_m(x, y) = buffers[10][std::size_t(x)];
    });
    return guides;
}

GatherSettings aaf_gather_settings(const AafParams &params) {
    GatherSettings settings;
    settings.normal_threshold_deg = params.normal_threshold_deg;
    settings.mode = params.mode == AafFilterMode::Separable ? GatherMode::Separable : GatherMode::Full2D;
    settings.symmetric_borders = params.symmetric_borders;
    return settings;
}

void aaf_filter(const AafInputs &in, const LightPlane &light, const AafParams &params,
                const AafOutputs &out) {
    check_inputs(in, light, params);
    const int width = in.visibility.width, height = in.visibility.height;
    if (!out.filtered_visibility.valid() || out.filtered_visibility.width != width ||
        out.filtered_visibility.height != height)
        throw Error("AAF output 'filtered visibility' is missing or has another size");

    // beta goes straight to its output, and the visibility is filtered in its
    // output's plane: no frame-sized copy beside the guides (peak memory).
    aaf_filter_visibility(aaf_gather_guides(in, light, params, out.beta_m), params, in.visibility,
                          out.filtered_visibility);
}

void aaf_filter_visibility(const GatherGuides &guides, const AafParams &params, ConstPlaneView visibility,
                           PlaneView filtered_visibility) {
    const int width = guides.width, height = guides.height;
    check_size(visibility, width, height, "visibility");
    if (!filtered_visibility.valid() || filtered_visibility.width != width ||
        filtered_visibility.height != height)
        throw Error("AAF output 'filtered visibility' is missing or has another size");
    // Non-finite visibility (a renderer's NaN) is read as 0, so it cannot spread through the filter.
    parallel_for_rows(height, [&](int y) {
        for (int x = 0; x < width; ++x) {
            const float v = visibility(x, y);
            filtered_visibility(x, y) = std::isfinite(v) ? v : 0.0f;
        }
    });
    aaf_gather(guides, params, {filtered_visibility}, {filtered_visibility});
}

}  // namespace aaf
