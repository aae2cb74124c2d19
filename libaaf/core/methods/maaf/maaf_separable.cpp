#include "aaf/core/maaf_separable.h"

#include <algorithm>
#include <cmath>

#include "aaf/core/parallel.h"

namespace aaf {

namespace {

constexpr float kPi = 3.14159265358979323846f;

/// One 1D pass: every pixel gathers the taps along `vertical` (columns) or
/// rows within its own radius, with its own kernel.
std::vector<ComplexPlane> pass(const GatherGuides &g, float cos_threshold, const ComplexKernels &k,
                               const std::vector<ComplexPlane> &sources, bool vertical) {
    const std::size_t count = std::size_t(g.width) * std::size_t(g.height);
    std::vector<ComplexPlane> out(sources.size());
    for (ComplexPlane &plane : out) {
        plane.re.assign(count, 0.0);
        plane.im.assign(count, 0.0);
    }
    parallel_for_rows(g.height, [&](int y) {
        for (int x = 0; x < g.width; ++x) {
            const std::size_t c = g.index(x, y);
            const int radius = k.radius_px[c];
            if (radius == 0) {
                for (std::size_t s = 0; s < sources.size(); ++s) {
                    out[s].re[c] = sources[s].re[c];
                    out[s].im[c] = sources[s].im[c];
                }
                continue;
            }
            const float u = g.coord_u_m[c], v = g.coord_v_m[c], id = g.object_id[c];
            const float nx = g.normal_x[c], ny = g.normal_y[c], nz = g.normal_z[c];
            const double omega_u = k.omega_u[c], omega_v = k.omega_v[c];
            const double inv_u = k.inv_u[c], inv_v = k.inv_v[c];
            const int begin = std::max(0, (vertical ? y : x) - radius);
            const int end = std::min(vertical ? g.height : g.width, (vertical ? y : x) + radius + 1);
            for (int tap = begin; tap < end; ++tap) {
                const std::size_t t = vertical ? g.index(x, tap) : g.index(tap, y);
                const float cos_angle = nx * g.normal_x[t] + ny * g.normal_y[t] + nz * g.normal_z[t];
                const bool accepted = t == c || (g.object_id[t] == id && cos_angle >= cos_threshold);
                if (!accepted) continue;
                const double du = double(g.coord_u_m[t]) - u, dv = double(g.coord_v_m[t]) - v;
                const double weight = std::exp(-(du * du * inv_u + dv * dv * inv_v));
                const double phase = omega_u * du + omega_v * dv;  // MAAF Eq. 12: e^{j (C_x x + ...)}
                const double wc = weight * std::cos(phase), ws = weight * std::sin(phase);
                for (std::size_t s = 0; s < sources.size(); ++s) {
                    const double re = sources[s].re[t], im = sources[s].im[t];
                    out[s].re[c] += wc * re - ws * im;
                    out[s].im[c] += wc * im + ws * re;
                }
            }
        }
    });
    return out;
}

}  // namespace

std::vector<ComplexPlane> maaf_separable_gather(const GatherGuides &guides, float normal_threshold_deg,
                                                const ComplexKernels &kernels,
                                                const std::vector<ComplexPlane> &sources) {
    const float cos_threshold = std::cos(normal_threshold_deg * kPi / 180.0f);
    // e^{j w.(d1 + d2)} = e^{j w.d1} e^{j w.d2}: along the column into (x, y'), then along the row.
    return pass(guides, cos_threshold, kernels, pass(guides, cos_threshold, kernels, sources, true), false);
}

}  // namespace aaf
