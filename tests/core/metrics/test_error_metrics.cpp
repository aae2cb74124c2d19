#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "aaf/core/metrics/error_metrics.h"
#include "aaf/core/util/error.h"

using namespace aaf;

namespace {

AovSet constant_rgb(int width, int height, float value) {
    AovSet image(width, height);
    for (const char *c : {"R", "G", "B"}) image.add_channel(c, value);
    return image;
}

}  // namespace

TEST_CASE("A constant offset gives closed-form metrics", "[metrics]") {
    const AovSet reference = constant_rgb(16, 12, 0.5f), test = constant_rgb(16, 12, 0.6f);
    CompareOptions options;
    options.compute_ssim = true;
    const ErrorMetrics m = compare_images(test, reference, options);
    const double d = double(0.6f) - double(0.5f);
    CHECK(m.mse == Approx(d * d));
    CHECK(m.rmse == Approx(d));
    CHECK(m.mae == Approx(d));
    CHECK(m.relmse == Approx(d * d / (0.25 + 0.01)));
    CHECK(m.psnr == Approx(20.0));  // 10 log10(1 / 0.01)
    // Flat images: variances and covariance vanish, SSIM = (2 a b + C1) / (a^2 + b^2 + C1).
    CHECK(m.ssim == Approx((2 * 0.5 * 0.6 + 1e-4) / (0.25 + 0.36 + 1e-4)).epsilon(1e-5));
    CHECK(m.pixels == 16u * 12u);
    CHECK(m.nonfinite_pixels == 0u);
}

TEST_CASE("A single-pixel difference is averaged over pixels and channels", "[metrics]") {
    const AovSet reference = constant_rgb(10, 10, 0.25f);
    AovSet test = constant_rgb(10, 10, 0.25f);
    test.channel("G")(3, 4) = 1.25f;
    const ErrorMetrics m = compare_channels(test, reference, {"R", "G", "B"});
    CHECK(m.mse == Approx(1.0 / 300.0));
    CHECK(m.mae == Approx(1.0 / 300.0));
}

TEST_CASE("Identical images: zero error, infinite PSNR, SSIM 1", "[metrics]") {
    AovSet image = constant_rgb(20, 20, 0.0f);
    for (int y = 0; y < 20; ++y)
        for (int x = 0; x < 20; ++x) image.channel("R")(x, y) = 0.05f * float((x * 7 + y * 3) % 11);
    CompareOptions options;
    options.compute_ssim = true;
    const ErrorMetrics m = compare_images(image, image, options);
    CHECK(m.mse == 0.0);
    CHECK(std::isinf(m.psnr));
    CHECK(m.ssim == Approx(1.0).epsilon(1e-6));
}

TEST_CASE("NaN and Inf pixels are counted and left out", "[metrics]") {
    const AovSet reference = constant_rgb(4, 4, 0.5f);
    AovSet test = constant_rgb(4, 4, 0.5f);
    test.channel("R")(0, 0) = std::nanf("");
    test.channel("B")(1, 0) = INFINITY;
    const ErrorMetrics m = compare_channels(test, reference, {"R", "G", "B"});
    CHECK(m.nonfinite_pixels == 2u);
    CHECK(m.pixels == 14u);
    CHECK(m.mse == 0.0);
}

TEST_CASE("Crop and mask select the compared pixels", "[metrics]") {
    const AovSet reference = constant_rgb(8, 8, 0.0f);
    AovSet test = constant_rgb(8, 8, 0.0f);
    test.channel("R")(6, 6) = 3.0f;  // outside the crop
    test.channel("R")(1, 1) = 0.3f;
    CompareOptions options;
    options.channels = {"R"};
    options.crop = PixelRect{0, 0, 4, 4};
    CHECK(compare_images(test, reference, options).mse == Approx(0.09 / 16));
    std::vector<float> mask(64, 0.0f);
    mask[1 * 8 + 1] = 1.0f;
    options.mask = plane_view(mask.data(), 8, 8);
    const ErrorMetrics masked = compare_images(test, reference, options);
    CHECK(masked.pixels == 1u);
    CHECK(masked.mse == Approx(0.09));

    options.crop = PixelRect{6, 6, 4, 4};
    CHECK_THROWS_WITH(compare_images(test, reference, options), Catch::Contains("outside"));
    CHECK_THROWS_WITH(compare_channels(test, reference, {"Z"}), Catch::Contains("'Z'"));
    CHECK_THROWS_WITH(compare_channels(test, constant_rgb(4, 8, 0), {"R"}), Catch::Contains("sizes differ"));
}

TEST_CASE("temporal_rmse: the RMSE of the change of the error between frames, over pixels compared in both",
          "[metrics]") {
    auto frame_error = [](float test_value, float reference_value, float nan_at_0) {
        AovSet test(3, 1), reference(3, 1);
        for (const char *c : {"R", "G", "B"}) {
            test.add_channel(c, test_value);
            reference.add_channel(c, reference_value);
        }
        test.channel("G")(0, 0) = nan_at_0;
        ErrorImage error;
        const ErrorMetrics m = compare_images(test, reference, {}, &error);
        CHECK(std::isnan(m.temporal_rmse));  // needs the previous frame
        return error;
    };
    const ErrorImage still = frame_error(0.7f, 0.5f, 0.7f), still_again = frame_error(0.9f, 0.7f, 0.9f);
    CHECK(temporal_rmse(still, still_again) == Approx(0.0).margin(1e-6));
    const ErrorImage up = frame_error(0.8f, 0.5f, 0.8f);
    CHECK(temporal_rmse(still, up) == Approx(0.1).epsilon(1e-5));
    // A pixel not compared in one frame (a NaN) is left out of both.
    const ErrorImage up_but_nan = frame_error(0.8f, 0.5f, std::nanf(""));
    CHECK(up_but_nan.selected[0] == 0);
    CHECK(temporal_rmse(still, up_but_nan) == Approx(0.1).epsilon(1e-5));
    AovSet small(2, 1);
    for (const char *c : {"R", "G", "B"}) small.add_channel(c, 0.5f);
    ErrorImage small_error;
    compare_images(small, small, {}, &small_error);
    CHECK_THROWS_AS(temporal_rmse(still, small_error), InputError);
}
