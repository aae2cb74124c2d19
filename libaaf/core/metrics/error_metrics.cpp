#include "aaf/core/metrics/error_metrics.h"

#include <array>
#include <cmath>
#include <limits>

#include "aaf/core/kernels/fixed_gaussian.h"
#include "aaf/core/metrics/flip.h"
#include "aaf/core/util/error.h"

namespace aaf {

namespace {

std::string size_text(const AovSet &image) {
    return std::to_string(image.width()) + "x" + std::to_string(image.height());
}

/// Per-pixel luminance of the compared channels (Rec. 709 for three).
std::vector<float> luminance(const AovSet &image, const std::vector<std::string> &channels) {
    std::vector<float> y(image.pixel_count());
    const std::vector<float> weights =
        channels.size() == 3 ? std::vector<float>{0.2126f, 0.7152f, 0.0722f}
                             : std::vector<float>(channels.size(), 1.0f / float(channels.size()));
    for (std::size_t c = 0; c < channels.size(); ++c) {
        const ConstPlaneView plane = image.channel(channels[c]);
        for (int row = 0; row < image.height(); ++row)
            for (int x = 0; x < image.width(); ++x)
                y[std::size_t(row) * image.width() + x] += weights[c] * plane(x, row);
    }
    return y;
}

/// The SSIM map (Wang et al. 2004, Eq. 13) from Gaussian-weighted local
/// statistics; non-finite luminance is replaced by 0 so it cannot spread (those
/// pixels are not averaged anyway).
std::vector<float> ssim_map(std::vector<float> a, std::vector<float> b, int width, int height) {
    constexpr float kSigmaPx = 1.5f;                           // window: 11x11 (cut at ceil(3 sigma) = 5 px)
    constexpr float kC1 = 0.01f * 0.01f, kC2 = 0.03f * 0.03f;  // (K L)^2 with L = 1
    const std::size_t n = a.size();
    for (std::size_t i = 0; i < n; ++i) {
        if (!std::isfinite(a[i]) || !std::isfinite(b[i])) a[i] = b[i] = 0;
    }
    std::vector<float> aa(n), bb(n), ab(n);
    for (std::size_t i = 0; i < n; ++i) {
        aa[i] = a[i] * a[i];
        bb[i] = b[i] * b[i];
        ab[i] = a[i] * b[i];
    }
    auto blur = [&](const std::vector<float> &in) {
        std::vector<float> out(n);
        fixed_gaussian_filter(plane_view(in.data(), width, height), kSigmaPx,
                              plane_view(out.data(), width, height));
        return out;
    };
    const std::vector<float> mu_a = blur(a), mu_b = blur(b), e_aa = blur(aa), e_bb = blur(bb),
                             e_ab = blur(ab);
    std::vector<float> map(n);
    for (std::size_t i = 0; i < n; ++i) {
        const float var_a = e_aa[i] - mu_a[i] * mu_a[i], var_b = e_bb[i] - mu_b[i] * mu_b[i];
        const float cov = e_ab[i] - mu_a[i] * mu_b[i];
        map[i] = ((2 * mu_a[i] * mu_b[i] + kC1) * (2 * cov + kC2)) /
                 ((mu_a[i] * mu_a[i] + mu_b[i] * mu_b[i] + kC1) * (var_a + var_b + kC2));
    }
    return map;
}

/// The compared region (the crop, or the whole image), after checking that the
/// images, their channels, the crop and the mask fit together.
PixelRect compared_rect(const AovSet &test, const AovSet &reference, const CompareOptions &options) {
    if (test.width() != reference.width() || test.height() != reference.height())
        throw InputError("image sizes differ: " + size_text(test) + " vs " + size_text(reference));
    if (options.channels.empty()) throw Error("no channels to compare");
    for (const std::string &name : options.channels) {
        if (!test.has_channel(name)) throw InputError("test image has no channel '" + name + "'");
        if (!reference.has_channel(name)) throw InputError("reference image has no channel '" + name + "'");
    }
    const int width = test.width(), height = test.height();
    PixelRect rect{0, 0, width, height};
    if (options.crop) {
        rect = *options.crop;
        if (!rect_within(rect, width, height))
            throw InputError("crop " + std::to_string(rect.width) + "x" + std::to_string(rect.height) + "+" +
                             std::to_string(rect.x) + "+" + std::to_string(rect.y) + " lies outside the " +
                             size_text(test) + " image");
    }
    if (options.mask.valid() && (options.mask.width != width || options.mask.height != height))
        throw InputError("mask is " + std::to_string(options.mask.width) + "x" +
                         std::to_string(options.mask.height) + ", images are " + size_text(test));
    return rect;
}

/// MSE, RMSE, MAE, relMSE and PSNR over the pixels inside `rect` and the mask
/// whose every channel is finite in both images; marks those pixels in
/// `selected` (SSIM and FLIP pool the same ones) and counts the others.
void add_pixel_errors(const std::vector<ConstPlaneView> &a, const std::vector<ConstPlaneView> &b,
                      const PixelRect &rect, int width, const CompareOptions &options,
                      std::vector<unsigned char> &selected, ErrorMetrics &m, ErrorImage *error) {
    double sum_sq = 0, sum_abs = 0, sum_rel = 0;
    for (int y = rect.y; y < rect.y + rect.height; ++y)
        for (int x = rect.x; x < rect.x + rect.width; ++x) {
            if (options.mask.valid() && options.mask(x, y) == 0) continue;
            bool finite = true;
            for (std::size_t c = 0; c < a.size(); ++c)
                finite = finite && std::isfinite(a[c](x, y)) && std::isfinite(b[c](x, y));
            if (!finite) {
                ++m.nonfinite_pixels;
                continue;
            }
            selected[std::size_t(y) * width + x] = 1;
            ++m.pixels;
            for (std::size_t c = 0; c < a.size(); ++c) {
                const double ref = b[c](x, y), diff = double(a[c](x, y)) - ref;
                if (error) error->error[(std::size_t(y) * width + x) * a.size() + c] = float(diff);
                sum_sq += diff * diff;
                sum_abs += std::abs(diff);
                sum_rel += diff * diff / (ref * ref + options.relmse_epsilon);
            }
        }
    const double count = double(m.pixels) * double(a.size());
    const double nan = std::numeric_limits<double>::quiet_NaN();
    m.mse = count > 0 ? sum_sq / count : nan;
    m.rmse = std::sqrt(m.mse);
    m.mae = count > 0 ? sum_abs / count : nan;
    m.relmse = count > 0 ? sum_rel / count : nan;
    m.psnr = m.mse > 0 ? 10.0 * std::log10(options.psnr_peak * options.psnr_peak / m.mse)
                       : (m.mse == 0 ? std::numeric_limits<double>::infinity() : nan);
}

/// FLIP (HDR or LDR, as the options say) of the RGB planes `a` against the
/// reference `b`, pooled over the selected pixels.
FlipSummary pooled_flip(const std::vector<ConstPlaneView> &a, const std::vector<ConstPlaneView> &b, int width,
                        int height, const CompareOptions &options,
                        const std::vector<unsigned char> &selected) {
    // Non-finite values would spread through FLIP's filters: zero them (those pixels are not pooled).
    std::array<std::vector<float>, 3> a_rgb, b_rgb;
    RgbPlanes a_view, b_view;
    for (int c = 0; c < 3; ++c) {
        a_rgb[c].resize(std::size_t(width) * height);
        b_rgb[c].resize(std::size_t(width) * height);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                const std::size_t i = std::size_t(y) * width + x;
                a_rgb[c][i] = std::isfinite(a[c](x, y)) ? a[c](x, y) : 0.0f;
                b_rgb[c][i] = std::isfinite(b[c](x, y)) ? b[c](x, y) : 0.0f;
            }
        a_view[c] = plane_view(a_rgb[c].data(), width, height);
        b_view[c] = plane_view(b_rgb[c].data(), width, height);
    }
    FlipParams flip_params;
    flip_params.pixels_per_degree = options.flip_pixels_per_degree;
    const std::vector<float> map = options.flip == CompareOptions::Flip::Hdr
                                       ? hdr_flip(b_view, a_view, flip_params)
                                       : ldr_flip(b_view, a_view, flip_params);
    return summarize_flip(map, selected);
}

}  // namespace

bool rect_within(const PixelRect &rect, int width, int height) {
    using Wide = long long;
    return rect.width > 0 && rect.height > 0 && rect.x >= 0 && rect.y >= 0 &&
           Wide(rect.x) + rect.width <= width && Wide(rect.y) + rect.height <= height;
}

ErrorMetrics compare_images(const AovSet &test, const AovSet &reference, const CompareOptions &options,
                            ErrorImage *error) {
    const PixelRect rect = compared_rect(test, reference, options);
    std::vector<ConstPlaneView> a, b;
    for (const std::string &name : options.channels) {
        a.push_back(test.channel(name));
        b.push_back(reference.channel(name));
    }
    const int width = test.width(), height = test.height();
    std::vector<unsigned char> selected(test.pixel_count(), 0);  // finite and inside crop and mask
    ErrorMetrics m;
    if (error)
        *error = ErrorImage{width, height, a.size(), std::vector<float>(test.pixel_count() * a.size()), {}};
    add_pixel_errors(a, b, rect, width, options, selected, m, error);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    m.temporal_rmse = nan;
    m.ssim = nan;
    if (options.compute_ssim && m.pixels > 0) {
        const std::vector<float> map = ssim_map(luminance(test, options.channels),
                                                luminance(reference, options.channels), width, height);
        double sum = 0;
        for (std::size_t i = 0; i < map.size(); ++i)
            if (selected[i]) sum += map[i];
        m.ssim = sum / double(m.pixels);
    }
    m.flip_mean = m.flip_weighted_median = nan;
    if (options.flip != CompareOptions::Flip::Off && m.pixels > 0) {
        if (options.channels.size() != 3) throw Error("FLIP needs three (RGB) channels");
        const FlipSummary pooled = pooled_flip(a, b, width, height, options, selected);
        m.flip_mean = pooled.mean;
        m.flip_weighted_median = pooled.weighted_median;
    }
    if (error) error->selected = std::move(selected);
    return m;
}

double temporal_rmse(const ErrorImage &previous, const ErrorImage &current) {
    if (previous.width != current.width || previous.height != current.height ||
        previous.channels != current.channels)
        throw InputError("frame sizes differ: " + std::to_string(previous.width) + "x" +
                         std::to_string(previous.height) + " with " + std::to_string(previous.channels) +
                         " channels, then " + std::to_string(current.width) + "x" +
                         std::to_string(current.height) + " with " + std::to_string(current.channels));
    double sum_sq = 0;
    std::size_t pixels = 0;
    for (std::size_t i = 0; i < current.selected.size(); ++i) {
        if (!previous.selected[i] || !current.selected[i]) continue;
        ++pixels;
        for (std::size_t c = 0; c < current.channels; ++c) {
            const double change = double(current.error[i * current.channels + c]) -
                                  double(previous.error[i * current.channels + c]);
            sum_sq += change * change;
        }
    }
    if (pixels == 0) return std::numeric_limits<double>::quiet_NaN();
    return std::sqrt(sum_sq / (double(pixels) * double(current.channels)));
}

ErrorMetrics compare_channels(const AovSet &test, const AovSet &reference,
                              const std::vector<std::string> &channels) {
    CompareOptions options;
    options.channels = channels;
    return compare_images(test, reference, options);
}

}  // namespace aaf
