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

/// The frame laid out for maaf_line_pass(): image rows padded to `stride`
/// pixels, image columns to `column` pixels; guides and kernels by row for
/// the horizontal pass, guides, kernels and complex sources by column (each
/// column's arrays together, `margin` pixels of padding above and below,
/// object id NaN there) for the vertical pass.
struct LineFrame {
    std::vector<int> pu, pv;
    std::vector<float> sign_v;
    detail::MaafTerms terms;
    int width = 0, height = 0, stride = 0, column = 0;
    int margin = 0;                              ///< the largest reach in the frame, pixels
    std::size_t column_length = 0;               ///< margin + column + margin
    std::vector<float> row_guides, row_kernels;  ///< 6 and 3 N + 1 arrays of stride * height
    std::vector<float> column_guides;            ///< per column 6 arrays of column_length
    std::vector<float> column_kernels;           ///< per column 3 N + 1 arrays of `column`
    std::vector<float> column_sources;           ///< per column 4 * terms arrays of column_length

    std::size_t kernel_arrays() const { return 3 * std::size_t(terms.pairs) + 1; }
    std::size_t row_plane() const { return std::size_t(stride) * std::size_t(height); }
};

/// Pixel i's six guides and 3 N + 1 kernel values (LineFrame's order).
void pixel_values(const GatherGuides &g, const MaafPixelKernel &k, std::size_t i, int pairs, float *guide,
                  float *kernel) {
    guide[0] = g.coord_u_m[i];
    guide[1] = g.coord_v_m[i];
    guide[2] = g.normal_x[i];
    guide[3] = g.normal_y[i];
    guide[4] = g.normal_z[i];
    guide[5] = g.object_id[i];
    int widest = 0;
    for (int p = 0; p < pairs; ++p) {
        // Every component p appears in the term (p, 0): the widest term reaches max_p radius_p.
        const int radius = k.filtered ? k.radius_px[p] : 0;
        kernel[p] = k.inv_two_sigma_sq[p];
        kernel[pairs + p] = k.omega_x[p];
        kernel[2 * pairs + p] = float(radius);
        widest = std::max(widest, radius);
    }
    kernel[3 * pairs] = float(widest);
}

/// The guides and kernels, by row and by column; padding is never a tap.
void line_guides(const GatherGuides &g, const std::vector<MaafPixelKernel> &kernels, LineFrame &f) {
    const std::size_t arrays = f.kernel_arrays(), plane = f.row_plane(), stride = std::size_t(f.stride);
    const std::size_t column = std::size_t(f.column), length = f.column_length;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    f.row_guides.assign(6 * plane, 0.0f);
    std::fill(f.row_guides.begin() + std::ptrdiff_t(5 * plane), f.row_guides.end(), nan);
    f.row_kernels.assign(arrays * plane, 0.0f);
    f.column_guides.assign(std::size_t(f.width) * 6 * length, 0.0f);
    f.column_kernels.assign(std::size_t(f.width) * arrays * column, 0.0f);
    for (int x = 0; x < f.width; ++x)
        std::fill_n(f.column_guides.begin() + std::ptrdiff_t((std::size_t(x) * 6 + 5) * length), length, nan);
    constexpr int kBlock = detail::kMaafLinePadding;  // as column_sources
    parallel_for_rows((f.width + kBlock - 1) / kBlock, [&](int block) {
        float guide[6], kernel[3 * kMaafMaxPairs + 1];
        const int x_end = std::min(f.width, (block + 1) * kBlock);
        for (int y = 0; y < f.height; ++y)
            for (int x = block * kBlock; x < x_end; ++x) {
                const std::size_t i = g.index(x, y), r = std::size_t(y) * stride + std::size_t(x);
                pixel_values(g, kernels[i], i, f.terms.pairs, guide, kernel);
                const std::size_t gc = std::size_t(x) * 6 * length + std::size_t(f.margin + y);
                const std::size_t kc = std::size_t(x) * arrays * column + std::size_t(y);
                for (std::size_t q = 0; q < 6; ++q) {
                    f.row_guides[q * plane + r] = guide[q];
                    f.column_guides[gc + q * length] = guide[q];
                }
                for (std::size_t q = 0; q < arrays; ++q) {
                    f.row_kernels[q * plane + r] = kernel[q];
                    f.column_kernels[kc + q * column] = kernel[q];
                }
            }
    });
}

/// The complex sources by column: value re, value im, unoccluded re,
/// unoccluded im, `terms.size()` arrays each, with the frame's margin.
void column_sources(const GatherGuides &g, const std::vector<Term> &terms,
                    const std::vector<std::vector<float>> &value_sums,
                    const std::vector<std::vector<float>> &unoccluded_sums, LineFrame &f) {
    const std::size_t count = terms.size(), length = f.column_length, planes = 4 * count;
    f.column_sources.assign(std::size_t(f.width) * planes * length, 0.0f);
    // Tiles of kTile x kTile pixels: summed along rows (as the sums are read), then copied down columns.
    constexpr int kTile = detail::kMaafLinePadding;
    constexpr std::size_t kTilePixels = std::size_t(kTile) * std::size_t(kTile);
    parallel_for_rows((g.width + kTile - 1) / kTile, [&](int block) {
        const int x0 = block * kTile, columns = std::min(kTile, g.width - x0);
        std::vector<float> tile(planes * kTilePixels);  // [plane][row][column]
        for (int y0 = 0; y0 < g.height; y0 += kTile) {
            const int rows = std::min(kTile, g.height - y0);
            std::fill(tile.begin(), tile.end(), 0.0f);
            for (int r = 0; r < rows; ++r) {
                const std::size_t first = g.index(x0, y0 + r), row = std::size_t(r * kTile);
                // One channel's run of the row at a time: the loop over the tile's columns vectorises.
                auto add = [&](std::size_t q, float factor, const std::vector<float> &sums) {
                    float *__restrict s = &tile[q * kTilePixels + row];
                    const float *__restrict in = &sums[first];
                    for (int c = 0; c < columns; ++c) s[c] += factor * in[c];
                };
                for (std::size_t j = 0; j < count; ++j) {
                    for (const auto &[factor, channel] : terms[j].re) {
                        add(j, factor, value_sums[channel]);
                        add(2 * count + j, factor, unoccluded_sums[channel]);
                    }
                    for (const auto &[factor, channel] : terms[j].im) {
                        add(count + j, factor, value_sums[channel]);
                        add(3 * count + j, factor, unoccluded_sums[channel]);
                    }
                }
            }
            for (int c = 0; c < columns; ++c)
                for (std::size_t q = 0; q < planes; ++q) {
                    float *dst = &f.column_sources[(std::size_t(x0 + c) * planes + q) * length +
                                                   std::size_t(f.margin + y0)];
                    for (int r = 0; r < rows; ++r)
                        dst[r] = tile[q * kTilePixels + std::size_t(r * kTile + c)];
                }
        }
    });
}

/// Row y's guides for the horizontal pass, `margin` pixels of padding each side.
void padded_guides(const LineFrame &f, int y, std::size_t length, std::vector<float> &guides) {
    const std::size_t plane = f.row_plane(), stride = std::size_t(f.stride);
    guides.assign(6 * length, 0.0f);
    std::fill(guides.begin() + std::ptrdiff_t(5 * length), guides.end(),
              std::numeric_limits<float>::quiet_NaN());
    for (std::size_t q = 0; q < 6; ++q)
        std::copy_n(f.row_guides.begin() + std::ptrdiff_t(q * plane + std::size_t(y) * stride), stride,
                    guides.begin() + std::ptrdiff_t(q * length + std::size_t(f.margin)));
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

/// Rows [first, first + count) (count a multiple of kMaafLinePadding): the
/// vertical pass of every column into `intermediate` (by row, 4 * terms
/// arrays of margin + stride + margin per row), then each row's horizontal pass.
void filter_band(const LineFrame &f, const GatherGuides &g, const std::vector<MaafPixelKernel> &kernels,
                 const std::vector<Term> &terms, int first, int count, MaafFilteredSums &out) {
    const std::size_t planes = 4 * terms.size(), stride = std::size_t(f.stride);
    const std::size_t length = std::size_t(f.margin) + stride + std::size_t(f.margin);
    std::vector<float> intermediate(std::size_t(count) * planes * length, 0.0f), guides;
    std::vector<float> row_sums(2 * terms.size() * stride);
    const std::size_t arrays = f.kernel_arrays(), column = std::size_t(f.column);
    detail::MaafLine line;
    for (int x = 0; x < f.width; ++x) {  // vertical: centres down column x
        line.count = count;
        line.margin = f.margin;
        line.guides = f.column_guides.data() + std::size_t(x) * 6 * f.column_length + std::size_t(first);
        line.guide_stride = f.column_length;
        line.kernels = f.column_kernels.data() + std::size_t(x) * arrays * column + std::size_t(first);
        line.kernel_stride = column;
        line.sources =
            f.column_sources.data() + std::size_t(x) * planes * f.column_length + std::size_t(first);
        line.source_stride = f.column_length;
        line.out = intermediate.data() + std::size_t(f.margin) + std::size_t(x);
        line.out_centre_step = planes * length;
        line.out_plane_step = length;
        detail::maaf_line_pass(f.terms, line, true);
    }
    for (int y = first; y < std::min(first + count, f.height); ++y) {  // horizontal: along row y
        padded_guides(f, y, length, guides);
        line.count = f.stride;
        line.guides = guides.data();
        line.guide_stride = length;
        line.kernels = f.row_kernels.data() + std::size_t(y) * stride;
        line.kernel_stride = f.row_plane();
        line.sources = intermediate.data() + std::size_t(y - first) * planes * length;
        line.source_stride = length;
        line.out = row_sums.data();
        line.out_centre_step = 1;
        line.out_plane_step = stride;
        detail::maaf_line_pass(f.terms, line, false);
        finish_row(g, kernels, terms, y, stride, row_sums, out);
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
    LineFrame f;
    for (const Term &t : terms) {
        f.pu.push_back(t.pu);
        f.pv.push_back(t.pv);
        f.sign_v.push_back(t.sign_v);
    }
    f.terms = {pairs,       int(terms.size()), f.pu.data(),
               f.pv.data(), f.sign_v.data(),   std::cos(normal_threshold_deg * kPi / 180.0f)};
    constexpr int kPadding = detail::kMaafLinePadding;
    f.width = g.width;
    f.height = g.height;
    f.stride = (g.width + kPadding - 1) / kPadding * kPadding;
    f.column = (g.height + kPadding - 1) / kPadding * kPadding;
    // The margin is the largest reach, known only from the kernels: a first look at them.
    for (const MaafPixelKernel &k : kernels)
        for (int p = 0; p < pairs && k.filtered; ++p) f.margin = std::max(f.margin, k.radius_px[p]);
    f.column_length = std::size_t(f.margin) + std::size_t(f.column) + std::size_t(f.margin);
    line_guides(g, kernels, f);
    column_sources(g, terms, value_sums, unoccluded_sums, f);

    MaafFilteredSums out;
    out.numerator.assign(count, 0.0);
    out.denominator.assign(count, 0.0);
    out.central_numerator.assign(count, 0.0);
    out.central_denominator.assign(count, 0.0);
    // Bands of rows: a band's vertical pass feeds only its own rows' horizontal passes.
    constexpr int kBandRows = 2 * kPadding;
    const int bands = (f.column + kBandRows - 1) / kBandRows;
    parallel_for_rows(bands, [&](int band) {
        const int first = band * kBandRows;
        filter_band(f, g, kernels, terms, first, std::min(kBandRows, f.column - first), out);
    });
    return out;
}

}  // namespace aaf
