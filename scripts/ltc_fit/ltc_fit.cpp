// Fits the LTC table of libaaf/core/ltc_ggx.h (Heitz, Dupuy, Hill, Neubelt
// 2016, Sec. 4) to the tracer's GGX lobe (aaf/trace/shading/ggx.h) and writes it as
// C++ source. Regenerate the committed table with
//   cmake --build build --target ltc_fit && build/scripts/ltc_fit/ltc_fit 64
//   libaaf/trace/shading/ltc_ggx_table.cpp
// (scripts/ltc_fit/README.md; a few minutes on one core for 64 x 64).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "aaf/trace/shading/ggx.h"
#include "aaf/trace/shading/ltc_ggx.h"

namespace {

using aaf::Vec3d;
constexpr double kPi = 3.14159265358979323846;
/// Samples per technique of the fit's error: kErrorGrid^2 stratified points.
constexpr int kErrorGrid = 32;
/// Samples of the magnitude, Fresnel and mean-direction integrals: kMomentGrid^2.
constexpr int kMomentGrid = 256;

struct Mat3 {
    double m[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    Vec3d apply(Vec3d v) const {
        return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
                m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
    }
    double determinant() const {
        return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
               m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
               m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    }
    Mat3 inverse() const {
        const double det = determinant();
        Mat3 r;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                const int i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
                r.m[i][j] = (m[i1][j1] * m[i2][j2] - m[i1][j2] * m[i2][j1]) / det;
            }
        return r;
    }
};

/// The lobe of one cell: view direction and roughness, with its moments.
struct Lobe {
    Vec3d wo;
    double alpha = 1;
    double magnitude = 0, fresnel = 0;
    Vec3d mean_direction{0, 0, 1};
};

Lobe measure_lobe(double roughness, double cos_view) {
    Lobe lobe;
    lobe.alpha = roughness * roughness;
    lobe.wo = {std::sqrt(1 - cos_view * cos_view), 0, cos_view};
    Vec3d mean;
    for (int j = 0; j < kMomentGrid; ++j)
        for (int i = 0; i < kMomentGrid; ++i) {
            const Vec3d wi =
                aaf::ggx::sample(lobe.wo, lobe.alpha, (i + 0.5) / kMomentGrid, (j + 0.5) / kMomentGrid);
            const double value = aaf::ggx::cosine_weighted(lobe.wo, wi, lobe.alpha);
            const double pdf = aaf::ggx::sample_pdf(lobe.wo, wi, lobe.alpha);
            if (!(value > 0) || !(pdf > 0)) continue;
            lobe.magnitude += value / pdf;
            lobe.fresnel += value * aaf::ggx::schlick_weight(lobe.wo, wi) / pdf;
            mean = mean + wi * (value / pdf);
        }
    const double count = double(kMomentGrid) * kMomentGrid;
    lobe.magnitude /= count;
    lobe.fresnel /= count;
    mean.y = 0;  // isotropic: the lobe is symmetric about the x-z plane
    lobe.mean_direction = aaf::normalize(mean);
    return lobe;
}

/// An LTC of three parameters (Heitz et al.'s isotropic fit): M = [X Y Z] *
/// [[m00, 0, m02], [0, m11, 0], [0, 0, 1]], Z the lobe's mean direction.
struct Ltc {
    Mat3 m, m_inv;
    double det_inv = 1;

    Ltc(const Lobe &lobe, const std::array<double, 3> &p) {
        const Vec3d z = lobe.mean_direction, y{0, 1, 0}, x = aaf::cross(y, z);
        const double m00 = std::max(p[0], 1e-5), m11 = std::max(p[1], 1e-5), m02 = p[2];
        const Mat3 frame{{{x.x, y.x, z.x}, {x.y, y.y, z.y}, {x.z, y.z, z.z}}};
        const Mat3 shape{{{m00, 0, m02}, {0, m11, 0}, {0, 0, 1}}};
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                m.m[i][j] = 0;
                for (int k = 0; k < 3; ++k) m.m[i][j] += frame.m[i][k] * shape.m[k][j];
            }
        m_inv = m.inverse();
        det_inv = std::fabs(m_inv.determinant());
    }
    /// D(w) = D_o(w_o) |det M^-1| / |M^-1 w|^3, w_o = M^-1 w / |M^-1 w| (LTC Eq. 1).
    double density(Vec3d w) const {
        const Vec3d local = m_inv.apply(w);
        const double norm = aaf::length(local);
        const double cos_o = local.z / norm;
        if (!(cos_o > 0)) return 0;
        return cos_o / kPi * det_inv / (norm * norm * norm);
    }
    Vec3d sample(double u1, double u2) const {
        const double r = std::sqrt(u1), phi = 2 * kPi * u2;
        const Vec3d w_o{r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1 - u1))};
        return aaf::normalize(m.apply(w_o));
    }
};

/// Heitz et al.'s L3 error between magnitude * D and the lobe, by MIS of
/// samples from both (balance heuristic on the two densities).
double fit_error(const Lobe &lobe, const std::array<double, 3> &p) {
    const Ltc ltc(lobe, p);
    double error = 0;
    for (int j = 0; j < kErrorGrid; ++j)
        for (int i = 0; i < kErrorGrid; ++i) {
            const double u1 = (i + 0.5) / kErrorGrid, u2 = (j + 0.5) / kErrorGrid;
            for (int technique = 0; technique < 2; ++technique) {
                const Vec3d wi =
                    technique == 0 ? ltc.sample(u1, u2) : aaf::ggx::sample(lobe.wo, lobe.alpha, u1, u2);
                const double lobe_value = aaf::ggx::cosine_weighted(lobe.wo, wi, lobe.alpha);
                const double pdf_lobe = lobe_value > 0 ? aaf::ggx::sample_pdf(lobe.wo, wi, lobe.alpha) : 0;
                const double ltc_value = ltc.density(wi);
                const double difference = std::fabs(lobe_value / lobe.magnitude - ltc_value);
                const double pdf_sum = ltc_value + pdf_lobe;
                if (pdf_sum > 0) error += difference * difference * difference / pdf_sum;
            }
        }
    return error / (2.0 * kErrorGrid * kErrorGrid);
}

/// Nelder-Mead simplex minimisation (reflection 1, expansion 2, contraction
/// and shrink 1/2) from `start` with initial step `step`.
std::array<double, 3> nelder_mead(const Lobe &lobe, std::array<double, 3> start, double step) {
    constexpr int kDim = 3, kMaxIterations = 400;
    constexpr double kTolerance = 1e-7;
    std::array<std::array<double, 3>, kDim + 1> simplex;
    std::array<double, kDim + 1> value;
    for (int k = 0; k <= kDim; ++k) {
        simplex[k] = start;
        if (k > 0) simplex[k][k - 1] += step;
        value[k] = fit_error(lobe, simplex[k]);
    }
    for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
        std::array<int, kDim + 1> order{0, 1, 2, 3};
        std::sort(order.begin(), order.end(), [&](int a, int b) { return value[a] < value[b]; });
        const int best = order[0], worst = order[kDim], second = order[kDim - 1];
        if (std::fabs(value[worst] - value[best]) <= kTolerance * (std::fabs(value[best]) + 1e-20)) break;
        std::array<double, 3> centroid{0, 0, 0};
        for (int k = 0; k <= kDim; ++k)
            if (k != worst)
                for (int d = 0; d < kDim; ++d) centroid[d] += simplex[k][d] / kDim;
        auto along = [&](double t) {
            std::array<double, 3> point;
            for (int d = 0; d < kDim; ++d) point[d] = centroid[d] + t * (simplex[worst][d] - centroid[d]);
            return point;
        };
        const std::array<double, 3> reflected = along(-1);
        const double reflected_value = fit_error(lobe, reflected);
        if (reflected_value < value[best]) {
            const std::array<double, 3> expanded = along(-2);
            const double expanded_value = fit_error(lobe, expanded);
            if (expanded_value < reflected_value) {
                simplex[worst] = expanded;
                value[worst] = expanded_value;
            } else {
                simplex[worst] = reflected;
                value[worst] = reflected_value;
            }
        } else if (reflected_value < value[second]) {
            simplex[worst] = reflected;
            value[worst] = reflected_value;
        } else {
            const std::array<double, 3> contracted = along(reflected_value < value[worst] ? -0.5 : 0.5);
            const double contracted_value = fit_error(lobe, contracted);
            if (contracted_value < std::min(reflected_value, value[worst])) {
                simplex[worst] = contracted;
                value[worst] = contracted_value;
            } else {
                for (int k = 0; k <= kDim; ++k) {
                    if (k == best) continue;
                    for (int d = 0; d < kDim; ++d) simplex[k][d] = 0.5 * (simplex[k][d] + simplex[best][d]);
                    value[k] = fit_error(lobe, simplex[k]);
                }
            }
        }
    }
    int best = 0;
    for (int k = 1; k <= kDim; ++k)
        if (value[k] < value[best]) best = k;
    return simplex[best];
}

}  // namespace

int main(int argc, char **argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: ltc_fit SIZE OUTPUT.cpp\n");
        return 2;
    }
    const int n = std::atoi(argv[1]);
    if (n < 2 || n > 256) {
        std::fprintf(stderr, "ltc_fit: SIZE must lie in [2, 256]\n");
        return 2;
    }
    std::vector<std::array<double, 6>> table(std::size_t(n) * n);
    std::array<double, 3> row_start{1, 1, 0};
    // From the roughest row down (the smooth cosine-like lobes fit from the
    // identity), each cell starts from its fitted neighbour: the previous view
    // angle in its row, or the row above's first cell (table continuity).
    for (int i = n - 1; i >= 0; --i) {
        const double roughness = std::max(aaf::ltc_ggx::kMinRoughness, double(i) / (n - 1));
        std::array<double, 3> start = row_start;
        for (int j = 0; j < n; ++j) {
            const double v = double(j) / (n - 1);
            const double cos_view = std::max(aaf::ltc_ggx::kMinCosView, 1 - v * v);
            const Lobe lobe = measure_lobe(roughness, cos_view);
            const std::array<double, 3> fitted =
                nelder_mead(lobe, start, 0.05 * std::max(roughness * roughness, 0.01));
            if (j == 0) row_start = fitted;
            start = fitted;
            const Ltc ltc(lobe, fitted);
            const Mat3 &inv = ltc.m_inv;
            const double scale = inv.m[2][2];
            if (!(scale > 0)) {
                std::fprintf(stderr, "ltc_fit: cell (%d, %d) has M^-1[2][2] <= 0\n", i, j);
                return 1;
            }
            table[std::size_t(i) * n + j] = {inv.m[0][0] / scale, inv.m[0][2] / scale, inv.m[1][1] / scale,
                                             inv.m[2][0] / scale, lobe.magnitude,      lobe.fresnel};
        }
        std::fprintf(stderr, "row %d of %d fitted\n", n - i, n);
    }
    FILE *out = std::fopen(argv[2], "w");
    if (!out) {
        std::fprintf(stderr, "ltc_fit: cannot write %s\n", argv[2]);
        return 1;
    }
    std::fprintf(out,
                 "// Generated by scripts/ltc_fit/ltc_fit.cpp; do not edit. Regenerate with\n"
                 "//   cmake --build build --target ltc_fit && build/scripts/ltc_fit/ltc_fit %d "
                 "libaaf/trace/shading/ltc_ggx_table.cpp\n"
                 "// LTC fit (Heitz, Dupuy, Hill, Neubelt 2016) of the tracer's GGX lobe: per cell\n"
                 "// a, b, c, d of M^-1 = [[a, 0, b], [0, c, 0], [d, 0, 1]], magnitude, fresnel.\n"
                 "#include \"ltc_ggx_table.h\"\n\nnamespace aaf::ltc_ggx_table {\n\nconst int kSize = %d;\n"
                 "const float kData[] = {\n",
                 n, n);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const auto &c = table[std::size_t(i) * n + j];
            std::fprintf(out, "    %.9ef, %.9ef, %.9ef, %.9ef, %.9ef, %.9ef,  // roughness %d, view %d\n",
                         c[0], c[1], c[2], c[3], c[4], c[5], i, j);
        }
    std::fprintf(out, "};\n\n}  // namespace aaf::ltc_ggx_table\n");
    std::fclose(out);
    return 0;
}
