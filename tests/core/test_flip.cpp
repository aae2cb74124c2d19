#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "aaf/core/flip.h"

using namespace aaf;

namespace {

constexpr int kWidth = 40, kHeight = 30;

/// An RGB image whose channel c at (x, y) is value(x, y, c).
struct TestImage {
    std::vector<float> planes[3];
    template <typename Fn>
    explicit TestImage(const Fn &value) {
        for (int c = 0; c < 3; ++c)
            for (int y = 0; y < kHeight; ++y)
                for (int x = 0; x < kWidth; ++x) planes[c].push_back(value(x, y, c));
    }
    RgbPlanes view() const {
        return {plane_view(planes[0].data(), kWidth, kHeight), plane_view(planes[1].data(), kWidth, kHeight),
                plane_view(planes[2].data(), kWidth, kHeight)};
    }
};

float smooth(int x, int y, int c) { return 0.5f + 0.4f * std::sin(0.3f * x + 0.2f * y + c); }
float smooth_noisy(int x, int y, int c) {
    return std::clamp(smooth(x, y, c) + 0.1f * std::sin(1.7f * float(x * y) + 0.5f * c), 0.0f, 1.0f);
}
float checker(int x, int y, int c) {
    static const float a[3] = {0.9f, 0.2f, 0.1f}, b[3] = {0.1f, 0.3f, 0.8f};
    return ((x / 8 + y / 8) % 2) ? a[c] : b[c];
}
float hdr(int x, int y, int c) { return std::exp(3.0f * std::sin(0.21f * x) * std::cos(0.17f * y)) * (0.5f + 0.3f * c); }
float hdr_test(int x, int y, int c) { return hdr(x, y, c) * (1.0f + 0.2f * std::sin(0.9f * x + 1.3f * y + c)); }

}  // namespace

// Expected values: the method's formulas as NVlabs/flip's Python reference
// (python/flip_api.py) evaluates them with numpy and OpenCV's filter2D
// (2D kernels, replicated borders) on the same synthetic images, default 67.02
// pixels per degree; see scripts/flip_reference_values.md for how they were made.
TEST_CASE("LDR-FLIP matches the reference implementation on two pairs", "[metrics][flip]") {
    const TestImage reference(smooth), noisy(smooth_noisy);
    const FlipSummary a = summarize_flip(ldr_flip(reference.view(), noisy.view()));
    CHECK(a.mean == Approx(0.138399).margin(0.01));
    CHECK(a.weighted_median == Approx(0.161014).margin(0.01));

    const TestImage blocks(checker), shifted([](int x, int y, int c) { return checker(x + 1, y, c); });
    const FlipSummary b = summarize_flip(ldr_flip(blocks.view(), shifted.view()));
    CHECK(b.mean == Approx(0.185748).margin(0.01));
    CHECK(b.weighted_median == Approx(0.311693).margin(0.01));
}

TEST_CASE("HDR-FLIP matches the reference implementation", "[metrics][flip]") {
    const TestImage reference(hdr), test(hdr_test);
    const FlipSummary s = summarize_flip(hdr_flip(reference.view(), test.view()));
    CHECK(s.mean == Approx(0.079776).margin(0.01));
    CHECK(s.weighted_median == Approx(0.088835).margin(0.01));
}

TEST_CASE("FLIP of identical images is zero and errors stay in [0, 1]", "[metrics][flip]") {
    const TestImage image(smooth), other(checker);
    for (float v : ldr_flip(image.view(), image.view())) REQUIRE(v == 0.0f);
    for (float v : hdr_flip(image.view(), image.view())) REQUIRE(v == 0.0f);
    for (float v : ldr_flip(image.view(), other.view())) {
        REQUIRE(v >= 0.0f);
        REQUIRE(v <= 1.0f);
    }
    // Weighted median of 1, 1, 2: running sums 1, 2, 4 first exceed half the total (2) at the value 2.
    CHECK(summarize_flip({1.0f, 2.0f, 1.0f}).weighted_median == 2.0f);
    CHECK(summarize_flip({3.0f, 1.0f, 1.0f, 1.0f}).weighted_median == 3.0f);
    CHECK(summarize_flip({1.0f, 1.0f, 1.0f, 1.0f, 0.5f}).weighted_median == 1.0f);
    CHECK(summarize_flip({1.0f, 2.0f, 1.0f}).mean == Approx(4.0 / 3.0));
}
