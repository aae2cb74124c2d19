// FLIP and HDR-FLIP, written from the published method (HPG 2020, EG 2021,
// Ray Tracing Gems II ch. 19); constants as the papers give them.
#include "aaf/core/metrics/flip.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "aaf/core/util/error.h"
#include "aaf/core/util/parallel.h"

namespace aaf {

namespace {

constexpr float kPi = 3.14159265358979f;
// D65 white of the XYZ <-> L*a*b* / YCxCz conversions, and its inverse.
constexpr float kWhite[3] = {0.950428545f, 1.0f, 1.088900371f};
constexpr float kInvWhite[3] = {1.052156925f, 1.0f, 0.918357670f};
// FLIP constants (HPG 2020, Sec. 4): colour exponent, redistribution, feature width and exponent.
constexpr float kQc = 0.7f, kPc = 0.4f, kPt = 0.95f, kFeatureWidthDeg = 0.082f, kQf = 0.5f;
// Contrast sensitivity: a * sqrt(pi / b) * exp(-pi^2 x^2 / b) per channel (x in degrees);
// blue-yellow is a sum of two such Gaussians.
constexpr float kCsfA1[3] = {1.0f, 1.0f, 34.1f}, kCsfB1[3] = {0.0047f, 0.0053f, 0.04f};
constexpr float kCsfA2 = 13.5f, kCsfB2 = 0.025f;
// ACES filmic fit with the 0.6 pre-exposure folded in: (k0 x^2 + k1 x) / (k3 x^2 + k4 x + k5).
constexpr float kAces[6] = {0.6f * 0.6f * 2.51f, 0.6f * 0.03f, 0.0f,
                            0.6f * 0.6f * 2.43f, 0.6f * 0.59f, 0.14f};

struct Rgb {
    float r, g, b;
};

float srgb_to_linear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}
float linear_to_srgb(float c) {
    return c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

Rgb linear_to_xyz(Rgb c) {
    return {(10135552.0f * c.r + 8788810.0f * c.g + 4435075.0f * c.b) / 24577794.0f,
            (2613072.0f * c.r + 8788810.0f * c.g + 887015.0f * c.b) / 12288897.0f,
            (1425312.0f * c.r + 8788810.0f * c.g + 70074185.0f * c.b) / 73733382.0f};
}

Rgb xyz_to_linear(Rgb c) {
    return {3.241003275f * c.r - 1.537398934f * c.g - 0.498615861f * c.b,
            -0.969224334f * c.r + 1.875930071f * c.g + 0.041554224f * c.b,
            0.055639423f * c.r - 0.204011202f * c.g + 1.057148933f * c.b};
}

Rgb xyz_to_ycxcz(Rgb c) {
    const float x = c.r * kInvWhite[0], y = c.g * kInvWhite[1], z = c.b * kInvWhite[2];
    return {116.0f * y - 16.0f, 500.0f * (x - y), 200.0f * (y - z)};
}

Rgb ycxcz_to_xyz(Rgb c) {
    const float y = (c.r + 16.0f) / 116.0f;
    return {(y + c.g / 500.0f) * kWhite[0], y * kWhite[1], (y - c.b / 200.0f) * kWhite[2]};
}

/// CIE L*a*b* with the Hunt adjustment of chroma by 0.01 L (FLIP Sec. 4.1).
Rgb linear_to_hunt_lab(Rgb c) {
    const Rgb xyz = linear_to_xyz(c);
    constexpr float delta = 6.0f / 29.0f;
    auto f = [&](float t) {
        return t > delta * delta * delta ? std::cbrt(t) : t / (3.0f * delta * delta) + 4.0f / 29.0f;
    };
    const float fx = f(xyz.r * kInvWhite[0]), fy = f(xyz.g * kInvWhite[1]), fz = f(xyz.b * kInvWhite[2]);
    const float l = 116.0f * fy - 16.0f;
    return {l, 0.01f * l * 500.0f * (fx - fy), 0.01f * l * 200.0f * (fy - fz)};
}

/// HyAB distance: city-block in lightness, Euclidean in the chroma plane.
float hyab(Rgb a, Rgb b) {
    return std::fabs(a.r - b.r) + std::hypot(a.g - b.g, a.b - b.b);
}

/// A planar float image with edge-replicating separable convolution.
struct Plane {
    int width = 0, height = 0;
    std::vector<float> data;
    Plane(int w, int h) : width(w), height(h), data(std::size_t(w) * h, 0.0f) {}
    float &at(int x, int y) { return data[std::size_t(y) * width + x]; }
    float at(int x, int y) const { return data[std::size_t(y) * width + x]; }
};

/// Convolves rows with `kx` then columns with `ky` (odd lengths, centred),
/// replicating edge pixels. Loops run over contiguous pixels per tap so they
/// vectorise; each output sums its taps in a fixed order.
Plane convolve(const Plane &in, const std::vector<float> &kx, const std::vector<float> &ky) {
    const int rx = int(kx.size()) / 2, ry = int(ky.size()) / 2, width = in.width, height = in.height;
    Plane rows(width, height), out(width, height);
    parallel_for_rows(height, [&](int y) {
        std::vector<float> padded(std::size_t(width) + 2 * rx);
        for (int x = -rx; x < width + rx; ++x)
            padded[std::size_t(x + rx)] = in.at(std::clamp(x, 0, width - 1), y);
        float *dst = &rows.at(0, y);
        for (int i = 0; i <= 2 * rx; ++i) {
            const float weight = kx[i];
            const float *src = padded.data() + i;
            for (int x = 0; x < width; ++x) dst[x] += weight * src[x];
        }
    });
    parallel_for_rows(height, [&](int y) {
        float *dst = &out.at(0, y);
        for (int i = -ry; i <= ry; ++i) {
            const float weight = ky[i + ry];
            const float *src = &rows.at(0, std::clamp(y + i, 0, height - 1));
            for (int x = 0; x < width; ++x) dst[x] += weight * src[x];
        }
    });
    return out;
}

/// 1D contrast-sensitivity kernels: achromatic, red-green (each normalised to
/// sum 1 in 2D, which a separable pair does as a product), and the two terms
/// of blue-yellow, scaled so that their 2D sum has unit weight.
struct CsfKernels {
    std::vector<float> achromatic, red_green, blue_yellow_1, blue_yellow_2;
};

CsfKernels csf_kernels(float ppd) {
    const float max_b = std::max({kCsfB1[0], kCsfB1[1], kCsfB1[2], kCsfB2});
    const int radius = int(std::ceil(3.0f * std::sqrt(max_b / (2.0f * kPi * kPi)) * ppd));
    CsfKernels k;
    double sum_a = 0, sum_rg = 0, sum_by1 = 0, sum_by2 = 0;
    for (int i = -radius; i <= radius; ++i) {
        const float x2 = float(i) * float(i) / (ppd * ppd);  // degrees squared
        auto gaussian = [&](float b) { return std::exp(-kPi * kPi * x2 / b); };
        k.achromatic.push_back(gaussian(kCsfB1[0]));
        k.red_green.push_back(gaussian(kCsfB1[1]));
        // Each 2D term a sqrt(pi/b) e(x) e(y) splits into two 1D factors of sqrt(a sqrt(pi/b)).
        k.blue_yellow_1.push_back(std::sqrt(kCsfA1[2] * std::sqrt(kPi / kCsfB1[2])) * gaussian(kCsfB1[2]));
        k.blue_yellow_2.push_back(std::sqrt(kCsfA2 * std::sqrt(kPi / kCsfB2)) * gaussian(kCsfB2));
        sum_a += k.achromatic.back();
        sum_rg += k.red_green.back();
        sum_by1 += k.blue_yellow_1.back();
        sum_by2 += k.blue_yellow_2.back();
    }
    const double by_norm = std::sqrt(sum_by1 * sum_by1 + sum_by2 * sum_by2);
    for (std::size_t i = 0; i < k.achromatic.size(); ++i) {
        k.achromatic[i] = float(k.achromatic[i] / sum_a);
        k.red_green[i] = float(k.red_green[i] / sum_rg);
        k.blue_yellow_1[i] = float(k.blue_yellow_1[i] / by_norm);
        k.blue_yellow_2[i] = float(k.blue_yellow_2[i] / by_norm);
    }
    return k;
}

/// Edge (first derivative) and point (second derivative) detectors of a
/// Gaussian of sd = w/2 degrees; positive and negative weights of each
/// derivative sum to 1 and -1, the Gaussian to 1.
struct FeatureKernels {
    std::vector<float> gaussian, first, second;
};

FeatureKernels feature_kernels(float ppd) {
    const float sd = 0.5f * kFeatureWidthDeg * ppd;
    const int radius = int(std::ceil(3.0f * sd));
    FeatureKernels k;
    double sum = 0, first_pos = 0, first_neg = 0, second_pos = 0, second_neg = 0;
    for (int i = -radius; i <= radius; ++i) {
        const float x = float(i), g = std::exp(-x * x / (2.0f * sd * sd));
        const float d1 = -x * g, d2 = (x * x / (sd * sd) - 1.0f) * g;
        k.gaussian.push_back(g);
        k.first.push_back(d1);
        k.second.push_back(d2);
        sum += g;
        (d1 > 0 ? first_pos : first_neg) += std::fabs(d1);
        (d2 > 0 ? second_pos : second_neg) += std::fabs(d2);
    }
    for (std::size_t i = 0; i < k.gaussian.size(); ++i) {
        k.gaussian[i] = float(k.gaussian[i] / sum);
        k.first[i] = float(k.first[i] / (k.first[i] > 0 ? first_pos : first_neg));
        k.second[i] = float(k.second[i] / (k.second[i] > 0 ? second_pos : second_neg));
    }
    return k;
}

/// YCxCz planes of an sRGB-encoded image.
std::array<Plane, 3> to_ycxcz(const std::array<Plane, 3> &srgb) {
    std::array<Plane, 3> out{Plane(srgb[0].width, srgb[0].height), Plane(srgb[0].width, srgb[0].height),
                             Plane(srgb[0].width, srgb[0].height)};
    const int width = srgb[0].width;
    parallel_for_rows(srgb[0].height, [&](int y) {
        for (std::size_t i = std::size_t(y) * width; i < std::size_t(y + 1) * width; ++i) {
            const Rgb c =
                xyz_to_ycxcz(linear_to_xyz({srgb_to_linear(srgb[0].data[i]), srgb_to_linear(srgb[1].data[i]),
                                            srgb_to_linear(srgb[2].data[i])}));
            out[0].data[i] = c.r;
            out[1].data[i] = c.g;
            out[2].data[i] = c.b;
        }
    });
    return out;
}

/// Edge and point magnitudes of the normalised achromatic channel.
std::pair<Plane, Plane> features(const Plane &y_channel, const FeatureKernels &k) {
    Plane normalised(y_channel.width, y_channel.height);
    for (std::size_t i = 0; i < normalised.data.size(); ++i)
        normalised.data[i] = (y_channel.data[i] + 16.0f) / 116.0f;
    const Plane dx = convolve(normalised, k.first, k.gaussian),
                dy = convolve(normalised, k.gaussian, k.first);
    const Plane ddx = convolve(normalised, k.second, k.gaussian),
                ddy = convolve(normalised, k.gaussian, k.second);
    Plane edges(y_channel.width, y_channel.height), points(y_channel.width, y_channel.height);
    for (std::size_t i = 0; i < edges.data.size(); ++i) {
        edges.data[i] = std::hypot(dx.data[i], dy.data[i]);
        points.data[i] = std::hypot(ddx.data[i], ddy.data[i]);
    }
    return {edges, points};
}

std::vector<float> ldr_flip_planes(const std::array<Plane, 3> &reference_srgb,
                                   const std::array<Plane, 3> &test_srgb, float ppd) {
    const std::array<Plane, 3> ref = to_ycxcz(reference_srgb), test = to_ycxcz(test_srgb);
    const CsfKernels csf = csf_kernels(ppd);
    auto filtered = [&](const std::array<Plane, 3> &c) {
        Plane by = convolve(c[2], csf.blue_yellow_1, csf.blue_yellow_1);
        const Plane by2 = convolve(c[2], csf.blue_yellow_2, csf.blue_yellow_2);
        for (std::size_t i = 0; i < by.data.size(); ++i) by.data[i] += by2.data[i];
        return std::array<Plane, 3>{convolve(c[0], csf.achromatic, csf.achromatic),
                                    convolve(c[1], csf.red_green, csf.red_green), by};
    };
    const std::array<Plane, 3> ref_f = filtered(ref), test_f = filtered(test);

    // The largest colour difference: green against blue (FLIP Sec. 4.1).
    const float cmax = std::pow(hyab(linear_to_hunt_lab({0, 1, 0}), linear_to_hunt_lab({0, 0, 1})), kQc);
    const float pccmax = kPc * cmax;
    auto to_lab = [](const std::array<Plane, 3> &c, std::size_t i) {
        Rgb rgb = xyz_to_linear(ycxcz_to_xyz({c[0].data[i], c[1].data[i], c[2].data[i]}));
        rgb = {std::clamp(rgb.r, 0.0f, 1.0f), std::clamp(rgb.g, 0.0f, 1.0f), std::clamp(rgb.b, 0.0f, 1.0f)};
        return linear_to_hunt_lab(rgb);
    };

    const FeatureKernels fk = feature_kernels(ppd);
    // Named, not structured bindings: C++17 lambdas cannot capture those (clang rejects it).
    const auto ref_features = features(ref[0], fk), test_features = features(test[0], fk);
    const auto &ref_edges = ref_features.first, &ref_points = ref_features.second;
    const auto &test_edges = test_features.first, &test_points = test_features.second;

    std::vector<float> errors(ref[0].data.size());
    const int width = ref[0].width;
    parallel_for_rows(ref[0].height, [&](int y) {
        for (std::size_t i = std::size_t(y) * width; i < std::size_t(y + 1) * width; ++i) {
            float colour = std::pow(hyab(to_lab(ref_f, i), to_lab(test_f, i)), kQc);
            colour = colour < pccmax ? colour * kPt / pccmax
                                     : kPt + (colour - pccmax) / (cmax - pccmax) * (1.0f - kPt);
            const float feature_difference = std::max(std::fabs(ref_edges.data[i] - test_edges.data[i]),
                                                      std::fabs(ref_points.data[i] - test_points.data[i]));
            const float feature = std::pow(feature_difference / std::sqrt(2.0f), kQf);
            errors[i] = std::pow(colour, 1.0f - feature);
        }
    });
    return errors;
}

std::array<Plane, 3> copy_planes(const RgbPlanes &planes) {
    const int width = planes[0].width, height = planes[0].height;
    std::array<Plane, 3> out{Plane(width, height), Plane(width, height), Plane(width, height)};
    for (int c = 0; c < 3; ++c)
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) out[c].at(x, y) = planes[c](x, y);
    return out;
}

/// Refuses images of different sizes and a viewing distance with no meaning:
/// at 0 pixels per degree every filter kernel is a single NaN tap.
void check_inputs(const RgbPlanes &a, const RgbPlanes &b, const FlipParams &params) {
    for (int c = 0; c < 3; ++c)
        if (!a[c].valid() || !b[c].valid() || a[c].width != a[0].width || a[c].height != a[0].height ||
            b[c].width != a[0].width || b[c].height != a[0].height)
            throw Error("FLIP: the images and channels must all have one size");
    if (!(params.pixels_per_degree > 0) || !std::isfinite(params.pixels_per_degree))
        throw Error("FLIP: pixels per degree must be a positive finite number, not " +
                    std::to_string(params.pixels_per_degree));
}

float aces(float x) {
    const float value =
        (kAces[0] * x * x + kAces[1] * x + kAces[2]) / (kAces[3] * x * x + kAces[4] * x + kAces[5]);
    return std::isfinite(value) ? std::clamp(value, 0.0f, 1.0f) : 1.0f;
}

}  // namespace

std::vector<float> ldr_flip(const RgbPlanes &reference, const RgbPlanes &test, const FlipParams &params) {
    check_inputs(reference, test, params);
    return ldr_flip_planes(copy_planes(reference), copy_planes(test), params.pixels_per_degree);
}

std::vector<float> hdr_flip(const RgbPlanes &reference, const RgbPlanes &test, const FlipParams &params) {
    check_inputs(reference, test, params);
    const std::array<Plane, 3> ref = copy_planes(reference), tst = copy_planes(test);
    const std::size_t n = ref[0].data.size();

    // Exposure range (HDR-FLIP Sec. 4): x where the tone curve reaches t = 0.85 ...
    constexpr float t = 0.85f;
    const float qa = kAces[0] - t * kAces[3], qb = kAces[1] - t * kAces[4], qc = kAces[2] - t * kAces[5];
    const float x_max = (-qb + std::sqrt(qb * qb - 4.0f * qa * qc)) / (2.0f * qa);
    // ... against the reference's brightest and median luminance.
    std::vector<float> luminance(n);
    for (std::size_t i = 0; i < n; ++i)
        luminance[i] = 0.2126f * std::max(0.0f, ref[0].data[i]) + 0.7152f * std::max(0.0f, ref[1].data[i]) +
                       0.0722f * std::max(0.0f, ref[2].data[i]);
    std::sort(luminance.begin(), luminance.end());
    const float y_max = luminance.back();
    // The 50th percentile with linear interpolation between ranks.
    const double rank = 0.5 * double(n - 1);
    const std::size_t lo = std::size_t(rank);
    const float y_median =
        float(luminance[lo] + (rank - double(lo)) * (luminance[std::min(lo + 1, n - 1)] - luminance[lo]));
    float start = 0, stop = 0;
    if (y_max > 0) {
        start = std::log2(x_max / y_max);
        stop = y_median > 0 ? std::log2(x_max / y_median) : start;
    }
    const int exposures = params.exposures > 0 ? params.exposures : std::max(2, int(std::ceil(stop - start)));
    const float step = (stop - start) / float(std::max(exposures - 1, 1));

    std::vector<float> errors(n, 0.0f);
    for (int e = 0; e < exposures; ++e) {
        const float scale = std::exp2(start + float(e) * step);
        auto expose = [&](const std::array<Plane, 3> &image) {
            std::array<Plane, 3> out = image;
            for (Plane &plane : out)
                parallel_for_rows(plane.height, [&](int y) {
                    for (int x = 0; x < plane.width; ++x)
                        plane.at(x, y) = linear_to_srgb(aces(scale * std::max(0.0f, plane.at(x, y))));
                });
            return out;
        };
        const std::vector<float> ldr = ldr_flip_planes(expose(ref), expose(tst), params.pixels_per_degree);
        for (std::size_t i = 0; i < n; ++i) errors[i] = std::max(errors[i], ldr[i]);
    }
    return errors;
}

FlipSummary summarize_flip(const std::vector<float> &errors, const std::vector<unsigned char> &selected) {
    std::vector<float> values;
    for (std::size_t i = 0; i < errors.size(); ++i)
        if ((selected.empty() || selected[i]) && std::isfinite(errors[i])) values.push_back(errors[i]);
    FlipSummary summary;
    if (values.empty()) return summary;
    double total = 0;
    for (float v : values) total += v;
    summary.mean = total / double(values.size());
    // The weighted median of NVlabs/flip's Python tool (python/flip.py, weighted_percentile, commit
    // 313517b): sort, take the first index i whose running sum is >= half the total (numpy's
    // searchsorted, side "left"), and average the values at i and i + 1. Where i is the last index
    // (one value, or the largest holding more than half the total) the reference indexes past the end;
    // we take that last value.
    std::sort(values.begin(), values.end());
    double running = 0;
    std::size_t i = 0;
    for (; i + 1 < values.size(); ++i) {
        running += values[i];
        if (running >= 0.5 * total) break;
    }
    summary.weighted_median =
        i + 1 < values.size() ? 0.5 * (double(values[i]) + double(values[i + 1])) : double(values[i]);
    return summary;
}

}  // namespace aaf
