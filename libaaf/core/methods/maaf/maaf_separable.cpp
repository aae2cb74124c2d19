#include "aaf/core/methods/maaf/maaf_separable.h"

#include <algorithm>
#include <cmath>

#include "aaf/core/kernels/fast_exp.h"
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

/// The terms' component indices as flat arrays for the tap loops; `padded`
/// rounds the count up to a multiple of 8 (zero weights) so the sums vectorise.
struct TermTable {
    std::size_t count = 0, padded = 0;
    std::vector<int> pu, pv;
    std::vector<float> sign_v;
    explicit TermTable(const std::vector<Term> &terms)
        : count(terms.size()), padded((terms.size() + 7) / 8 * 8) {
        for (const Term &t : terms) {
            pu.push_back(t.pu);
            pv.push_back(t.pv);
            sign_v.push_back(t.sign_v);
        }
    }
};

/// Per-tap x-side factors of one centre's kernels: the Gaussians and phase
/// factors of every component along both axes, then each term's complex weight.
struct TapWeights {
    float gauss_u[kMaafMaxPairs], gauss_v[kMaafMaxPairs];
    float cos_u[kMaafMaxPairs], sin_u[kMaafMaxPairs], cos_v[kMaafMaxPairs], sin_v[kMaafMaxPairs];

    void evaluate(const MaafPixelKernel &k, int pairs, float du, float dv) {
        for (int p = 0; p < pairs; ++p) {
            gauss_u[p] = fast_exp_nonpositive(-du * du * k.inv_two_sigma_sq[p]);
            gauss_v[p] = fast_exp_nonpositive(-dv * dv * k.inv_two_sigma_sq[p]);
        }
        cos_u[0] = cos_v[0] = 1.0f;
        sin_u[0] = sin_v[0] = 0.0f;
        for (int p = 1; p < pairs; ++p) {  // e^{j C_x^p du}, shared by every pair with p on that axis
            cos_u[p] = std::cos(k.omega_x[p] * du);
            sin_u[p] = std::sin(k.omega_x[p] * du);
            cos_v[p] = std::cos(k.omega_x[p] * dv);
            sin_v[p] = std::sin(k.omega_x[p] * dv);
        }
    }
    /// Every term's weight g_p(du) g_q(dv) e^{j (C_x^p du + sign_v C_x^q dv)} (MAAF Eq. 12) into re[j],
    /// im[j]; 0 for a term whose reach `radius` is below the tap's `offset` (pixels).
    void of_terms(const TermTable &t, const int *radius, int offset, float *re, float *im) const {
        for (std::size_t j = 0; j < t.count; ++j) {
            const int pu = t.pu[j], pv = t.pv[j];
            const float a = cos_u[pu], b = sin_u[pu], c = cos_v[pv], d = t.sign_v[j] * sin_v[pv];
            const float g = offset <= radius[j] ? gauss_u[pu] * gauss_v[pv] : 0.0f;
            re[j] = g * (a * c - b * d);
            im[j] = g * (a * d + b * c);
        }
    }
};

/// The complex sources, pixel-interleaved so that one tap's terms are
/// contiguous: per pixel four blocks of `padded` floats (value re, value im,
/// unoccluded re, unoccluded im).
std::vector<float> complex_sources(const GatherGuides &g, const std::vector<Term> &terms, std::size_t padded,
                                   const std::vector<std::vector<float>> &value_sums,
                                   const std::vector<std::vector<float>> &unoccluded_sums) {
    const std::size_t stride = 4 * padded;
    std::vector<float> sources(std::size_t(g.width) * std::size_t(g.height) * stride, 0.0f);
    parallel_for_rows(g.height, [&](int y) {
        for (int x = 0; x < g.width; ++x) {
            const std::size_t i = g.index(x, y);
            float *s = &sources[i * stride];
            for (std::size_t j = 0; j < terms.size(); ++j) {
                for (const auto &[factor, c] : terms[j].re) {
                    s[j] += factor * value_sums[c][i];
                    s[2 * padded + j] += factor * unoccluded_sums[c][i];
                }
                for (const auto &[factor, c] : terms[j].im) {
                    s[padded + j] += factor * value_sums[c][i];
                    s[3 * padded + j] += factor * unoccluded_sums[c][i];
                }
            }
        }
    });
    return sources;
}

/// The two passes over one frame's complex sources: a row's vertical pass
/// feeds only that row's horizontal pass, so one row's intermediates exist
/// at a time (RowBuffers, allocated once per row).
class SeparablePasses {
  public:
    SeparablePasses(const GatherGuides &g, float normal_threshold_deg,
                    const std::vector<MaafPixelKernel> &kernels, int pairs, const std::vector<Term> &terms,
                    const std::vector<float> &sources)
        : g_(g),
          kernels_(kernels),
          pairs_(pairs),
          terms_(terms),
          table_(terms),
          sources_(sources),
          cos_threshold_(std::cos(normal_threshold_deg * kPi / 180.0f)) {}

    /// One row's scratch: the vertical pass's output, one centre's sums, the
    /// terms' weights and reaches.
    struct RowBuffers {
        std::vector<float> intermediate, sum, re, im;
        std::vector<int> radius;
        TapWeights w;
        RowBuffers(int width, std::size_t padded, std::size_t term_count)
            : intermediate(std::size_t(width) * 4 * padded),
              sum(4 * padded),
              re(padded, 0.0f),
              im(padded, 0.0f),
              radius(term_count) {}
    };
    RowBuffers row_buffers() const { return RowBuffers(g_.width, table_.padded, table_.count); }

    /// Vertical: each pixel of row y with its own kernel, into b.intermediate.
    void vertical(int y, RowBuffers &b) const {
        const std::size_t padded = table_.padded, stride = 4 * padded;
        for (int x = 0; x < g_.width; ++x) {
            const std::size_t c = g_.index(x, y);
            const MaafPixelKernel &k = kernels_[c];
            const int widest = term_radii(k, b.radius.data());
            float *acc = &b.intermediate[std::size_t(x) * stride];
            if (widest == 0) {
                std::copy_n(&sources_[c * stride], stride, acc);
                continue;
            }
            std::fill(b.sum.begin(), b.sum.end(), 0.0f);
            for (int ty = std::max(0, y - widest); ty <= std::min(g_.height - 1, y + widest); ++ty) {
                const std::size_t t = g_.index(x, ty);
                if (!accepted(c, t)) continue;
                const int offset = std::abs(ty - y);
                b.w.evaluate(k, pairs_, g_.coord_u_m[t] - g_.coord_u_m[c], g_.coord_v_m[t] - g_.coord_v_m[c]);
                b.w.of_terms(table_, b.radius.data(), offset, b.re.data(), b.im.data());
                const float *s = &sources_[t * stride];
                // Distinct buffers: restrict lets the compiler vectorise over the terms.
                float *__restrict sum_v = b.sum.data(), *__restrict sum_u = b.sum.data() + 2 * padded;
                const float *__restrict src_v = s, *__restrict src_u = s + 2 * padded;
                const float *__restrict wr = b.re.data(), *__restrict wi = b.im.data();
                for (std::size_t j = 0; j < padded; ++j) {  // complex weight times complex source
                    sum_v[j] += wr[j] * src_v[j] - wi[j] * src_v[padded + j];
                    sum_v[padded + j] += wr[j] * src_v[padded + j] + wi[j] * src_v[j];
                    sum_u[j] += wr[j] * src_u[j] - wi[j] * src_u[padded + j];
                    sum_u[padded + j] += wr[j] * src_u[padded + j] + wi[j] * src_u[j];
                }
            }
            std::copy(b.sum.begin(), b.sum.end(), acc);
        }
    }

    /// Horizontal: each centre of row y with its own kernel over the vertical
    /// pass's output, real parts only, then MAAF Eq. 21's weighted sums.
    void horizontal(int y, RowBuffers &b, MaafFilteredSums &out) const {
        const std::size_t padded = table_.padded, stride = 4 * padded;
        for (int x = 0; x < g_.width; ++x) {
            const std::size_t c = g_.index(x, y);
            const MaafPixelKernel &k = kernels_[c];
            if (!k.filtered) continue;
            const int widest = term_radii(k, b.radius.data());
            std::fill(b.sum.begin(), b.sum.end(), 0.0f);
            for (int tx = std::max(0, x - widest); tx <= std::min(g_.width - 1, x + widest); ++tx) {
                const std::size_t t = g_.index(tx, y);
                if (!accepted(c, t)) continue;
                const int offset = std::abs(tx - x);
                b.w.evaluate(k, pairs_, g_.coord_u_m[t] - g_.coord_u_m[c], g_.coord_v_m[t] - g_.coord_v_m[c]);
                b.w.of_terms(table_, b.radius.data(), offset, b.re.data(), b.im.data());
                const float *s = &b.intermediate[std::size_t(tx) * stride];
                float *__restrict sum_v = b.sum.data(), *__restrict sum_u = b.sum.data() + 2 * padded;
                const float *__restrict src_v = s, *__restrict src_u = s + 2 * padded;
                const float *__restrict wr = b.re.data(), *__restrict wi = b.im.data();
                for (std::size_t j = 0; j < padded; ++j) {  // real parts only
                    sum_v[j] += wr[j] * src_v[j] - wi[j] * src_v[padded + j];
                    sum_u[j] += wr[j] * src_u[j] - wi[j] * src_u[padded + j];
                }
            }
            double numerator = 0, denominator = 0;
            for (std::size_t j = 0; j < table_.count;
                 ++j) {  // MAAF Eq. 21: mu_p sigma_p mu_q sigma_q per pair
                const double weight = terms_[j].scale * k.weight[terms_[j].pu] * k.weight[terms_[j].pv];
                numerator += weight * double(b.sum[j]);
                denominator += weight * double(b.sum[2 * padded + j]);
            }
            out.numerator[c] = numerator;
            out.denominator[c] = denominator;
            out.central_numerator[c] = double(b.sum[0]);
            out.central_denominator[c] = double(b.sum[2 * padded]);
        }
    }

  private:
    /// gather()'s tap test: the centre always, else the same object with a normal within the threshold.
    bool accepted(std::size_t c, std::size_t t) const {
        const float cos_angle = g_.normal_x[c] * g_.normal_x[t] + g_.normal_y[c] * g_.normal_y[t] +
                                g_.normal_z[c] * g_.normal_z[t];
        return t == c || (g_.object_id[t] == g_.object_id[c] && cos_angle >= cos_threshold_);
    }
    /// Each term's reach at a pixel: max(radius_p, radius_q); 0 where it is not filtered. Returns the widest.
    int term_radii(const MaafPixelKernel &k, int *radius) const {
        int widest = 0;
        for (std::size_t j = 0; j < table_.count; ++j) {
            radius[j] = k.filtered ? std::max(k.radius_px[terms_[j].pu], k.radius_px[terms_[j].pv]) : 0;
            widest = std::max(widest, radius[j]);
        }
        return widest;
    }

    const GatherGuides &g_;
    const std::vector<MaafPixelKernel> &kernels_;
    const int pairs_;
    const std::vector<Term> &terms_;
    const TermTable table_;
    const std::vector<float> &sources_;
    const float cos_threshold_;
};

}  // namespace

MaafFilteredSums maaf_separable_filter(const GatherGuides &g, float normal_threshold_deg,
                                       const std::vector<MaafPixelKernel> &kernels, int sum_pairs, int pairs,
                                       const std::vector<std::vector<float>> &value_sums,
                                       const std::vector<std::vector<float>> &unoccluded_sums) {
    if (pairs < 1 || pairs > sum_pairs || sum_pairs > kMaafMaxPairs)
        throw Error("MAAF separable filter: N used must lie in [1, N of the sums]");
    const std::size_t count = std::size_t(g.width) * std::size_t(g.height);
    const std::vector<Term> terms = terms_for(sum_pairs, pairs);
    const std::vector<float> sources =
        complex_sources(g, terms, TermTable(terms).padded, value_sums, unoccluded_sums);
    const SeparablePasses passes(g, normal_threshold_deg, kernels, pairs, terms, sources);

    MaafFilteredSums out;
    out.numerator.assign(count, 0.0);
    out.denominator.assign(count, 0.0);
    out.central_numerator.assign(count, 0.0);
    out.central_denominator.assign(count, 0.0);
    parallel_for_rows(g.height, [&](int y) {
        SeparablePasses::RowBuffers buffers = passes.row_buffers();
        passes.vertical(y, buffers);
        passes.horizontal(y, buffers, out);
    });
    return out;
}

}  // namespace aaf
