#pragma once

#include <optional>
#include <string>
#include <vector>

#include "aaf/core/contract/aov_set.h"

namespace aaf {

/// A pixel rectangle [x, x + width) x [y, y + height).
struct PixelRect {
    int x = 0, y = 0, width = 0, height = 0;
};

/// True when `rect` is non-empty and lies within a `width` x `height` image;
/// computed in 64 bits, so no x + width wraps past INT_MAX into the image.
bool rect_within(const PixelRect &rect, int width, int height);

/// What to compare and how. The defaults measure R, G, B over the whole image.
struct CompareOptions {
    std::vector<std::string> channels{"R", "G", "B"};
    std::optional<PixelRect> crop;  ///< only pixels inside; must lie within the image
    ConstPlaneView mask;            ///< optional, same size: only pixels where mask != 0
    /// Relative MSE: (test - ref)^2 / (ref^2 + epsilon), the convention of
    /// Rousselle et al. and pbrt-v4's imgtool with epsilon = 0.01.
    double relmse_epsilon = 0.01;
    /// PSNR peak value. Renders are HDR, so there is no natural white: the
    /// default 1 is display white of linear images; pass the reference's
    /// maximum for a data-range PSNR.
    double psnr_peak = 1.0;
    bool compute_ssim = false;  ///< SSIM costs a few blurs; off unless asked for
    /// FLIP of three channels: LDR-FLIP for sRGB-encoded images in [0, 1]
    /// (PNG), HDR-FLIP for linear images (EXR); see flip.h.
    enum class Flip { Off, Ldr, Hdr } flip = Flip::Off;
    float flip_pixels_per_degree = 67.0206f;  ///< FLIP's default viewing condition
};

/// Error of a test image against a reference.
struct ErrorMetrics {
    double mse = 0;     ///< mean over pixels and channels of (test - ref)^2
    double rmse = 0;    ///< sqrt(mse)
    double mae = 0;     ///< mean of |test - ref|
    double relmse = 0;  ///< mean of (test - ref)^2 / (ref^2 + epsilon)
    double psnr = 0;    ///< 10 log10(peak^2 / mse) dB; +inf when mse = 0
    /// Mean SSIM (Wang et al. 2004) of the luminance (Rec. 709 weights of
    /// three channels, or the single channel), 11x11 Gaussian window of
    /// sigma 1.5 px, K1 = 0.01, K2 = 0.03, dynamic range L = 1; NaN unless asked.
    double ssim = 0;
    double flip_mean = 0;             ///< FLIP pooled by the mean; NaN unless asked
    double flip_weighted_median = 0;  ///< FLIP's weighted median; NaN unless asked
    /// Temporal error of a sequence: the RMSE, over the pixels compared in
    /// both frames and the channels, of the frame-to-frame change of the
    /// error, (test_t - ref_t) - (test_t-1 - ref_t-1). A still, exact
    /// sequence and one whose error is the same every frame score 0; residual
    /// noise that changes every frame (flicker) scores about sqrt(2) times
    /// its RMSE. NaN for a single image and a sequence's first frame.
    double temporal_rmse = 0;
    std::size_t pixels = 0;            ///< pixels compared (finite in both images)
    std::size_t nonfinite_pixels = 0;  ///< selected pixels skipped for a NaN/Inf in either image
};

/// The signed error test - reference of the compared channels at the
/// compared pixels, kept to measure the next frame's temporal error.
struct ErrorImage {
    int width = 0, height = 0;
    std::size_t channels = 0;
    std::vector<float> error;             ///< pixel-major, `channels` values per pixel
    std::vector<unsigned char> selected;  ///< 1 where the pixel was compared
};

/// Compares the selected channels of `test` against the same channels of
/// `reference`. Pixels with a NaN or Inf in any compared channel of either
/// image are counted in `nonfinite_pixels` and left out of every average.
/// Throws aaf::InputError on a size mismatch, a missing channel (naming it and
/// the image), a crop that is empty or outside the image or a mask of another
/// size.
/// With `error` non-null, also stores the signed error image there
/// (temporal_rmse is left NaN: it needs the previous frame).
ErrorMetrics compare_images(const AovSet &test, const AovSet &reference, const CompareOptions &options = {},
                            ErrorImage *error = nullptr);

/// ErrorMetrics::temporal_rmse of a frame from its error image and the
/// previous frame's. NaN when no pixel was compared in both. Throws
/// aaf::InputError when the frames differ in size or channel count.
double temporal_rmse(const ErrorImage &previous, const ErrorImage &current);

/// compare_images over `channels`, whole image.
ErrorMetrics compare_channels(const AovSet &test, const AovSet &reference,
                              const std::vector<std::string> &channels);

}  // namespace aaf
