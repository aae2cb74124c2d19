// AAF's own gather (aaf_gather(), the separable passes of AAF Sec. 6)
// against a straightforward formulation of the same equations on a rendered
// `grids` frame: each tap's weight exp(-d^2 / (2 beta^2)) (AAF Eq. 11) in
// double precision with std::exp, d the distance in the light's plane (AAF
// Eq. 12) slid along the light as GatherGuides documents. The kernel takes
// the exponential in base 2 with a degree-4 polynomial and rounds every
// multiply and add in float; on this frame it stays within 3.6e-7 of the
// reference (measured at 160x120, 9 spp; 7.7e-7 from the former fused
// kernel at 640x480), so 1e-5 leaves room for another compiler's rounding
// while a wrong tap, weight or test (a shift of a percent) fails it.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/methods/aaf/aaf_filter.h"
#include "aaf/core/util/instruction_set.h"
#include "aaf/core/util/thread_count.h"
#include "aaf/trace/render.h"

using namespace aaf;

namespace {

constexpr int kWidth = 160, kHeight = 120;

struct Grids {
    AovSet aovs;
    AafInputs inputs;
    LightPlane light;
    Grids() {
        trace::RenderSettings settings;
        settings.width = kWidth;
        settings.height = kHeight;
        settings.spp = 9;
        settings.seed = 5;
        aovs = trace::render_scene("grids", settings);
        inputs.visibility = aovs.channel("shadow.V");
        inputs.d1 = aovs.channel("shadow.d1");
        inputs.d2_min = aovs.channel("shadow.d2min");
        inputs.d2_max = aovs.channel("shadow.d2max");
        inputs.position = {aovs.channel("P.X"), aovs.channel("P.Y"), aovs.channel("P.Z")};
        inputs.normal = {aovs.channel("N.X"), aovs.channel("N.Y"), aovs.channel("N.Z")};
        inputs.object_id = aovs.channel("id.object");
        inputs.pixel_size = aovs.channel("pixel.size");
        light = read_light_attributes(aovs);
    }
};

/// One 1D pass of the separable gather at pixel c over the taps c + o step,
/// |o| <= reach, in double precision. The object and normal tests are the
/// kernel's own float expression, so a tap on the threshold's edge is
/// decided alike (a yes/no, not a rounding).
double reference_pixel(const GatherGuides &g, float cos_threshold, const std::vector<double> &source,
                       std::size_t c, long step, int reach) {
    const bool sheared = g.sheared();
    const double inv_u = g.inv_two_sigma_sq[c], inv_v = g.anisotropic() ? g.inv_two_sigma_sq_v[c] : inv_u;
    double sum = 0, weight_sum = 0;
    for (int o = -reach; o <= reach; ++o) {
        const std::size_t t = std::size_t(long(c) + long(o) * step);
        const float cos_angle =
            (g.normal_x[c] * g.normal_x[t] + g.normal_y[c] * g.normal_y[t]) + g.normal_z[c] * g.normal_z[t];
        if (!(g.object_id[t] == g.object_id[c] && cos_angle >= cos_threshold)) continue;
        double du = double(g.coord_u_m[t]) - g.coord_u_m[c], dv = double(g.coord_v_m[t]) - g.coord_v_m[c];
        double dn = 0;
        if (sheared) {
            dn = double(g.coord_n_m[t]) - g.coord_n_m[c];
            du -= g.shear_u[c] * dn;
            dv -= g.shear_v[c] * dn;
        }
        const double weight_n = sheared ? dn * dn * double(g.inv_two_sigma_sq_n[c]) : 0.0;
        const double weight = std::exp(-(du * du * inv_u + dv * dv * inv_v) - weight_n);  // AAF Eq. 11
        sum += weight * source[t];
        weight_sum += weight;
    }
    const float nx = g.normal_x[c], ny = g.normal_y[c], nz = g.normal_z[c];
    if (!((nx * nx + ny * ny) + nz * nz >= cos_threshold && g.object_id[c] == g.object_id[c])) {
        sum += source[c];  // the centre always counts
        weight_sum += 1;
    }
    return sum / weight_sum;
}

/// AAF Sec. 6's two passes, along y then along x, with symmetric borders
/// (AafParams' default): a window cut by an edge is cut on the other side too.
std::vector<double> reference_gather(const GatherGuides &g, float cos_threshold,
                                     const std::vector<double> &in) {
    std::vector<double> vertical(in), out(in);
    for (int pass = 0; pass < 2; ++pass) {
        const std::vector<double> &source = pass == 0 ? in : vertical;
        std::vector<double> &target = pass == 0 ? vertical : out;
        for (int y = 0; y < g.height; ++y)
            for (int x = 0; x < g.width; ++x) {
                const std::size_t c = g.index(x, y);
                if (g.radius_px[c] == 0) continue;  // keeps its value
                const int reach = pass == 0 ? std::min({g.radius_px[c], y, g.height - 1 - y})
                                            : std::min({g.radius_px[c], x, g.width - 1 - x});
                target[c] = reference_pixel(g, cos_threshold, source, c, pass == 0 ? g.width : 1, reach);
            }
    }
    return out;
}

std::vector<float> filtered_visibility(const Grids &grids) {
    std::vector<float> out(std::size_t(kWidth) * kHeight);
    aaf_filter(grids.inputs, grids.light, AafParams{}, {plane_view(out.data(), kWidth, kHeight), {}});
    return out;
}

}  // namespace

TEST_CASE("AAF gather: within 1e-5 of AAF Eq. 11-12 in double precision on grids", "[aaf][gather]") {
    const Grids grids;
    const AafParams params;
    const GatherGuides guides = aaf_gather_guides(grids.inputs, grids.light, params);
    REQUIRE(guides.sheared());  // the default slides taps along the light
    std::vector<double> visibility(guides.radius_px.size());
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const float v = grids.inputs.visibility(x, y);
            visibility[guides.index(x, y)] = std::isfinite(v) ? v : 0.0;
        }
    const float cos_threshold = std::cos(params.normal_threshold_deg * 3.14159265358979323846f / 180.0f);
    const std::vector<double> expected = reference_gather(guides, cos_threshold, visibility);
    const std::vector<float> filtered = filtered_visibility(grids);
    double worst = 0;
    int smoothed = 0;
    for (std::size_t i = 0; i < expected.size(); ++i) {
        worst = std::max(worst, std::fabs(double(filtered[i]) - expected[i]));
        smoothed += std::fabs(expected[i] - visibility[i]) > 0.01;
    }
    INFO("max |aaf.V - reference| = " << worst << " over " << expected.size() << " pixels");
    CHECK(worst <= 1e-5);
    CHECK(smoothed > int(expected.size()) / 10);  // the filter does filter this frame
}

TEST_CASE("AAF gather: the same bytes on every instruction set and thread count", "[aaf][gather][simd]") {
    const Grids grids;
    const InstructionSet before = instruction_set();
    set_instruction_set(InstructionSet::Sse42);
    std::vector<float> reference;
    run_with_threads(1, [&] { reference = filtered_visibility(grids); });
    for (const InstructionSet set : {InstructionSet::Sse42, InstructionSet::Avx2, InstructionSet::Avx512}) {
        if (!cpu_supports(set)) continue;
        set_instruction_set(set);
        for (const int threads : {1, 2, 3}) {
            std::vector<float> out;
            run_with_threads(threads, [&] { out = filtered_visibility(grids); });
            INFO("instruction set " << int(set) << ", " << threads << " threads");
            CHECK(std::memcmp(out.data(), reference.data(), out.size() * sizeof(float)) == 0);
        }
    }
    set_instruction_set(before);
}
