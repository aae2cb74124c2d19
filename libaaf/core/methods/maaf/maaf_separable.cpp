#include "aaf/core/methods/maaf/maaf_separable.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "aaf/core/methods/maaf/maaf_separable_rows.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/parallel.h"

namespace aaf {

namespace {

constexpr float kPi = 3.14159265358979323846f;

/// One complex source of MAAF Eq. 13 regrouped: the channels' combination
/// filtered with g_p(du) g_q(dv) e^{j (C_x^p du + sign_v C_x^q dv)}, its real
/// part entering the result times `scale` mu_p sigma_p mu_q sigma_q.
struct Term {
    int pu = 0, pv = 0;
    float sign_v = 1.0f;
    double scale = 1.0;
    std::vector<std::pair<float, std::size_t>> re, im;  ///< (factor, channel)
};

/// The terms for N = `pairs` over sums accumulated with `sum_pairs`; term 0 is the central pair.
std::vector<Term> terms_for(int sum_pairs, int pairs) {
    const int per_axis = maaf_functions_per_axis(sum_pairs);
    auto channel = [per_axis](int function_u, int function_v) {
        return std::size_t(function_u * per_axis + function_v);
    };
    // For p, q >= 1 (a, b the two axes' x-side phases):
    // cos a cos b h_cc - cos a sin b h_cs - sin a cos b h_sc + sin a sin b h_ss
    //   = 1/2 Re[e^{j(a+b)} ((h_cc - h_ss) + j (h_cs + h_sc))]
    //   + 1/2 Re[e^{j(a-b)} ((h_cc + h_ss) + j (h_sc - h_cs))],
    // and cos a h_c - sin a h_s = Re[e^{ja} (h_c + j h_s)] with one axis central.
    std::vector<Term> terms;
    for (int pu = 0; pu < pairs; ++pu)
        for (int pv = 0; pv < pairs; ++pv) {
            if (pu == 0 && pv == 0) {
                terms.push_back({0, 0, 1.0f, 1.0, {{1.0f, channel(0, 0)}}, {}});
            } else if (pv == 0) {
                terms.push_back(
                    {pu, 0, 1.0f, 1.0, {{1.0f, channel(2 * pu - 1, 0)}}, {{1.0f, channel(2 * pu, 0)}}});
            } else if (pu == 0) {
                terms.push_back(
                    {0, pv, 1.0f, 1.0, {{1.0f, channel(0, 2 * pv - 1)}}, {{1.0f, channel(0, 2 * pv)}}});
            } else {
                const std::size_t cc = channel(2 * pu - 1, 2 * pv - 1), cs = channel(2 * pu - 1, 2 * pv),
                                  sc = channel(2 * pu, 2 * pv - 1), ss = channel(2 * pu, 2 * pv);
                terms.push_back({pu, pv, 1.0f, 0.5, {{1.0f, cc}, {-1.0f, ss}}, {{1.0f, cs}, {1.0f, sc}}});
                terms.push_back({pu, pv, -1.0f, 0.5, {{1.0f, cc}, {1.0f, ss}}, {{1.0f, sc}, {-1.0f, cs}}});
            }
        }
    return terms;
}

/// The frame's planes for the row kernels (maaf_separable_rows.h), owned:
/// guides, kernels and complex sources, rows padded to kMaafRowPadding.
struct PlanarFrame {
    std::vector<int> term_pu, term_pv;
    std::vector<float> term_sign_v;
    std::vector<float> coord_u, coord_v, normal_x, normal_y, normal_z, object_id;
    std::vector<float> inv_two_sigma_sq, omega, radius_px, widest_px, sources;
    int widest = 0;  ///< the largest reach in the frame, pixels
    detail::MaafSeparableFrame view;
};

/// The guides and each pixel's kernels, planar; padding columns are never taps.
void planar_kernels(const GatherGuides &g, const std::vector<MaafPixelKernel> &kernels, int pairs,
                    PlanarFrame &f) {
    const std::size_t stride = std::size_t(f.view.stride), plane = stride * std::size_t(g.height);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (auto *v : {&f.coord_u, &f.coord_v, &f.normal_x, &f.normal_y, &f.normal_z, &f.widest_px})
        v->assign(plane, 0.0f);
    f.object_id.assign(plane, nan);
    f.inv_two_sigma_sq.assign(std::size_t(pairs) * plane, 0.0f);
    f.omega.assign(std::size_t(pairs) * plane, 0.0f);
    f.radius_px.assign(std::size_t(pairs) * plane, 0.0f);
    for (int y = 0; y < g.height; ++y)
        for (int x = 0; x < g.width; ++x) {
            const std::size_t i = g.index(x, y), o = std::size_t(y) * stride + std::size_t(x);
            f.coord_u[o] = g.coord_u_m[i];
            f.coord_v[o] = g.coord_v_m[i];
            f.normal_x[o] = g.normal_x[i];
            f.normal_y[o] = g.normal_y[i];
            f.normal_z[o] = g.normal_z[i];
            f.object_id[o] = g.object_id[i];
            const MaafPixelKernel &k = kernels[i];
            int widest = 0;
            for (int p = 0; p < pairs; ++p) {
                // Every component p appears in the term (p, 0): the widest term reaches max_p radius_p.
                const int radius = k.filtered ? k.radius_px[p] : 0;
                f.inv_two_sigma_sq[std::size_t(p) * plane + o] = k.inv_two_sigma_sq[p];
                f.omega[std::size_t(p) * plane + o] = k.omega_x[p];
                f.radius_px[std::size_t(p) * plane + o] = float(radius);
                widest = std::max(widest, radius);
            }
            f.widest_px[o] = float(widest);
            f.widest = std::max(f.widest, widest);
        }
}

/// The complex sources, planar: value re, value im, unoccluded re,
/// unoccluded im, `terms.size()` planes each.
void planar_sources(const GatherGuides &g, const std::vector<Term> &terms,
                    const std::vector<std::vector<float>> &value_sums,
                    const std::vector<std::vector<float>> &unoccluded_sums, PlanarFrame &f) {
    const std::size_t stride = std::size_t(f.view.stride), plane = stride * std::size_t(g.height);
    const std::size_t count = terms.size();
    f.sources.assign(4 * count * plane, 0.0f);
    parallel_for_rows(g.height, [&](int y) {
        for (int x = 0; x < g.width; ++x) {
            const std::size_t i = g.index(x, y), o = std::size_t(y) * stride + std::size_t(x);
            for (std::size_t j = 0; j < count; ++j) {
                float *s = &f.sources[j * plane + o];
                for (const auto &[factor, c] : terms[j].re) {
                    s[0] += factor * value_sums[c][i];
                    s[2 * count * plane] += factor * unoccluded_sums[c][i];
                }
                for (const auto &[factor, c] : terms[j].im) {
                    s[count * plane] += factor * value_sums[c][i];
                    s[3 * count * plane] += factor * unoccluded_sums[c][i];
                }
            }
        }
    });
}

/// Row y's guides for the horizontal pass: coord_u, coord_v, normal x, y, z,
/// object id, each `row.length` long, NaN ids in the margins.
void padded_guides(const PlanarFrame &f, int y, detail::MaafPaddedRow row, std::vector<float> &guides) {
    const std::size_t length = std::size_t(row.length), stride = std::size_t(f.view.stride);
    guides.assign(6 * length, 0.0f);
    std::fill(guides.begin() + std::ptrdiff_t(5 * length), guides.end(),
              std::numeric_limits<float>::quiet_NaN());
    const std::size_t first = std::size_t(y) * stride, margin = std::size_t(row.margin);
    std::size_t q = 0;
    for (const std::vector<float> *plane :
         {&f.coord_u, &f.coord_v, &f.normal_x, &f.normal_y, &f.normal_z, &f.object_id}) {
        std::copy_n(plane->begin() + std::ptrdiff_t(first), stride,
                    guides.begin() + std::ptrdiff_t(q * length + margin));
        ++q;
    }
}

/// MAAF Eq. 21's weighted sums of one row from the horizontal pass's real parts.
void finish_row(const GatherGuides &g, const std::vector<MaafPixelKernel> &kernels,
                const std::vector<Term> &terms, int y, std::size_t stride, const std::vector<float> &row_sums,
                MaafFilteredSums &out) {
    const std::size_t count = terms.size();
    for (int x = 0; x < g.width; ++x) {
        const std::size_t c = g.index(x, y);
        const MaafPixelKernel &k = kernels[c];
        if (!k.filtered) continue;
        const auto sum = [&](std::size_t q) { return double(row_sums[q * stride + std::size_t(x)]); };
        double numerator = 0, denominator = 0;
        for (std::size_t j = 0; j < count; ++j) {  // MAAF Eq. 21: mu_p sigma_p mu_q sigma_q per pair
            const double weight = terms[j].scale * k.weight[terms[j].pu] * k.weight[terms[j].pv];
            numerator += weight * sum(j);
            denominator += weight * sum(count + j);
        }
        out.numerator[c] = numerator;
        out.denominator[c] = denominator;
        out.central_numerator[c] = sum(0);
        out.central_denominator[c] = sum(count);
    }
}

}  // namespace

MaafFilteredSums maaf_separable_filter(const GatherGuides &g, float normal_threshold_deg,
                                       const std::vector<MaafPixelKernel> &kernels, int sum_pairs, int pairs,
                                       const std::vector<std::vector<float>> &value_sums,
                                       const std::vector<std::vector<float>> &unoccluded_sums) {
    if (pairs < 1 || pairs > sum_pairs || sum_pairs > kMaafMaxPairs)
        throw Error("MAAF separable filter: N used must lie in [1, N of the sums]");
    const std::size_t count = std::size_t(g.width) * std::size_t(g.height);
    const std::vector<Term> terms = terms_for(sum_pairs, pairs);
    PlanarFrame f;
    detail::MaafSeparableFrame &view = f.view;
    view.width = g.width;
    view.height = g.height;
    view.stride = (g.width + detail::kMaafRowPadding - 1) / detail::kMaafRowPadding * detail::kMaafRowPadding;
    view.pairs = pairs;
    view.terms = int(terms.size());
    for (const Term &t : terms) {
        f.term_pu.push_back(t.pu);
        f.term_pv.push_back(t.pv);
        f.term_sign_v.push_back(t.sign_v);
    }
    view.term_pu = f.term_pu.data();
    view.term_pv = f.term_pv.data();
    view.term_sign_v = f.term_sign_v.data();
    view.cos_threshold = std::cos(normal_threshold_deg * kPi / 180.0f);
    planar_kernels(g, kernels, pairs, f);
    planar_sources(g, terms, value_sums, unoccluded_sums, f);
    view.coord_u = f.coord_u.data();
    view.coord_v = f.coord_v.data();
    view.normal_x = f.normal_x.data();
    view.normal_y = f.normal_y.data();
    view.normal_z = f.normal_z.data();
    view.object_id = f.object_id.data();
    view.inv_two_sigma_sq = f.inv_two_sigma_sq.data();
    view.omega = f.omega.data();
    view.radius_px = f.radius_px.data();
    view.widest_px = f.widest_px.data();
    view.sources = f.sources.data();

    MaafFilteredSums out;
    out.numerator.assign(count, 0.0);
    out.denominator.assign(count, 0.0);
    out.central_numerator.assign(count, 0.0);
    out.central_denominator.assign(count, 0.0);
    // A row's vertical pass feeds only that row's horizontal pass: one row's intermediates at a time.
    const detail::MaafPaddedRow row{f.widest, f.widest + view.stride + f.widest};
    const std::size_t stride = std::size_t(view.stride);
    parallel_for_rows(g.height, [&](int y) {
        std::vector<float> intermediate(4 * terms.size() * std::size_t(row.length), 0.0f), guides;
        std::vector<float> row_sums(2 * terms.size() * stride);
        detail::maaf_vertical_row(view, y, intermediate.data(), row);
        padded_guides(f, y, row, guides);
        detail::maaf_horizontal_row(view, y, intermediate.data(), guides.data(), row, row_sums.data());
        finish_row(g, kernels, terms, y, stride, row_sums, out);
    });
    return out;
}

}  // namespace aaf
