// The temporal window's blend (temporal_window.h): what it keeps, what it
// averages and what it rejects, on synthetic frames.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "aaf/core/framework/temporal_window.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/thread_count.h"

using namespace aaf;

namespace {

constexpr int kWidth = 64, kHeight = 48;

/// One synthetic frame: a plane z = 0 seen from above, one unit per pixel,
/// with one value layer; `shift_px` moves the camera (the scene slides left
/// by it per frame, the motion layer says so).
struct SyntheticFrame {
    std::vector<float> value, px, py, pz, nx, ny, nz, mx, my, id, size;
    SyntheticFrame(int frame, float shift_px, float (*shade)(float world_x, float world_y, int frame)) {
        const std::size_t pixels = std::size_t(kWidth) * kHeight;
        for (auto *plane : {&value, &px, &py, &pz, &nx, &ny, &nz, &mx, &my, &id, &size})
            plane->assign(pixels, 0);
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) {
                const std::size_t i = std::size_t(y) * kWidth + std::size_t(x);
                const float world_x = float(x) + shift_px * float(frame);
                px[i] = world_x;
                py[i] = float(y);
                nz[i] = 1;
                mx[i] = -shift_px;  // the surface point sat shift_px to the right in the previous frame
                id[i] = 1;
                size[i] = 1;
                value[i] = shade(world_x, float(y), frame);
            }
    }
    TemporalFrameView view(int offset) const {
        TemporalFrameView v;
        v.offset = offset;
        v.values = {ConstPlaneView(plane_view(value.data(), kWidth, kHeight))};
        v.position = {plane_view(px.data(), kWidth, kHeight), plane_view(py.data(), kWidth, kHeight),
                      plane_view(pz.data(), kWidth, kHeight)};
        v.normal = {plane_view(nx.data(), kWidth, kHeight), plane_view(ny.data(), kWidth, kHeight),
                    plane_view(nz.data(), kWidth, kHeight)};
        v.motion = {plane_view(mx.data(), kWidth, kHeight), plane_view(my.data(), kWidth, kHeight)};
        v.object_id = plane_view(id.data(), kWidth, kHeight);
        v.pixel_size_m = plane_view(size.data(), kWidth, kHeight);
        return v;
    }
};

/// Blends frames centre-K..centre+K of `frames` (index = frame number) around `centre`.
std::vector<float> blend(const std::vector<SyntheticFrame> &frames, int centre, int radius,
                         float tolerance = 3.0f) {
    TemporalWindowSettings settings;
    settings.radius_frames = radius;
    settings.shading_tolerance = tolerance;
    std::vector<TemporalFrameView> neighbours;
    for (int f = centre - radius; f <= centre + radius; ++f)
        if (f != centre) neighbours.push_back(frames[std::size_t(f)].view(f - centre));
    std::vector<float> out(std::size_t(kWidth) * kHeight);
    blend_temporal_window(frames[std::size_t(centre)].view(0), neighbours, settings,
                          {plane_view(out.data(), kWidth, kHeight)});
    return out;
}

float smooth_shade(float world_x, float world_y, int) {
    return 0.5f + 0.3f * std::sin(world_x * 0.21f) * std::cos(world_y * 0.17f);
}

/// Mean squared difference of `a` from the noise-free shade, over interior pixels.
double mse_from_truth(const std::vector<float> &a, int frame, float shift_px) {
    double sum = 0;
    int count = 0;
    for (int y = 4; y < kHeight - 4; ++y)
        for (int x = 12; x < kWidth - 12; ++x) {
            const double d = a[std::size_t(y) * kWidth + std::size_t(x)] -
                             smooth_shade(float(x) + shift_px * float(frame), float(y), frame);
            sum += d * d;
            ++count;
        }
    return sum / count;
}

std::vector<SyntheticFrame> noisy_frames(float shift_px, float noise) {
    std::vector<SyntheticFrame> frames;
    std::mt19937 random(7);
    std::normal_distribution<float> gaussian(0.0f, noise);
    for (int f = 0; f < 5; ++f) {
        frames.emplace_back(f, shift_px, smooth_shade);
        for (float &v : frames.back().value) v += gaussian(random);
    }
    return frames;
}

/// `count` frames of smooth_shade on a still camera, each pixel's value
/// replaced by value(frame, x, y, shade), pixels in row-major order.
template <typename Value>
std::vector<SyntheticFrame> still_frames(int count, const Value &value) {
    std::vector<SyntheticFrame> frames;
    for (int f = 0; f < count; ++f) {
        frames.emplace_back(0, 0.0f, smooth_shade);
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) {
                float &v = frames.back().value[std::size_t(y) * kWidth + std::size_t(x)];
                v = value(f, x, y, v);
            }
    }
    return frames;
}

/// Squared error of `values` from the noise-free shade over the pixels `inside(x, y)` selects.
template <typename Inside>
double error_within(const std::vector<float> &values, const Inside &inside) {
    double sum = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x)
            if (inside(x, y)) {
                const double d =
                    values[std::size_t(y) * kWidth + std::size_t(x)] - smooth_shade(float(x), float(y), 0);
                sum += d * d;
            }
    return sum;
}

}  // namespace

TEST_CASE("temporal window: a static frame whose neighbours hold the same values is unchanged, bit for bit",
          "[temporal]") {
    std::vector<SyntheticFrame> frames;
    for (int f = 0; f < 5; ++f) frames.emplace_back(0, 0.0f, smooth_shade);  // the same frame five times
    const std::vector<float> out = blend(frames, 2, 2);
    CHECK(std::memcmp(out.data(), frames[2].value.data(), out.size() * sizeof(float)) == 0);
}

TEST_CASE("temporal window: per-frame noise of a static frame averages down over the window", "[temporal]") {
    const std::vector<SyntheticFrame> frames = noisy_frames(0.0f, 0.05f);
    const double alone = mse_from_truth(frames[2].value, 2, 0.0f);
    const double blended = mse_from_truth(blend(frames, 2, 2), 2, 0.0f);
    // Five frames of independent noise: 1/5 of the variance with equal weights;
    // the shading test weighs pure noise at about 0.95.
    CHECK(blended < 0.3 * alone);
    CHECK(blended > 0.15 * alone);  // not smoothed in space: at best the five frames' mean
}

TEST_CASE("temporal window: a patch noisier than its surroundings averages down too", "[temporal]") {
    // A filter's residual noise changes within a frame (a narrow width in a
    // penumbra beside a wide one in the light): a 6 x 6 px patch with ten
    // times the noise of the rest, which sets the region's median.
    std::mt19937 random(11);
    std::normal_distribution<float> gaussian(0.0f, 1.0f);
    const auto in_patch = [](int x, int y) { return x >= 30 && x < 36 && y >= 20 && y < 26; };
    const std::vector<SyntheticFrame> frames = still_frames(5, [&](int, int x, int y, float shade) {
        return shade + (in_patch(x, y) ? 0.05f : 0.005f) * gaussian(random);
    });
    const double alone = error_within(frames[2].value, in_patch),
                 blended = error_within(blend(frames, 2, 2), in_patch);
    // Measured against its region alone, the patch's neighbours differ by
    // many times the noise there and would be rejected (blended == alone);
    // within three times the region's noise they average to 0.44 of it. Its
    // own spread lets them average nearly as five frames do (0.2).
    CHECK(blended < 0.3 * alone);
}

TEST_CASE(
    "temporal window: a noisy band in a noise-free region averages down once five values tell it from an "
    "edge",
    "[temporal]") {
    // A 3 px penumbra whose noise is the only noise of its region (the
    // ratio estimator is exact in full light and umbra): most of the
    // region's pixels never change.
    std::mt19937 random(5);
    std::normal_distribution<float> gaussian(0.0f, 0.05f);
    const auto in_band = [](int x, int) { return x >= 30 && x < 33; };
    const std::vector<SyntheticFrame> frames = still_frames(
        5, [&](int, int x, int y, float shade) { return in_band(x, y) ? shade + gaussian(random) : shade; });
    // Five values: each pixel's own spread shows noise, not a moving edge.
    CHECK(error_within(blend(frames, 2, 2), in_band) < 0.5 * error_within(frames[2].value, in_band));
    // Three: one changed value of three is not told from noise, so the band
    // (a minority of its region) is taken for a moving edge and kept.
    const std::vector<float> three = blend(frames, 2, 1);
    CHECK(std::memcmp(three.data(), frames[2].value.data(), three.size() * sizeof(float)) == 0);
}

TEST_CASE(
    "temporal window: a pixel that repeats its neighbours' value in the frame keeps it (a shadow "
    "passing in one frame)",
    "[temporal]") {
    // Noisy light everywhere; in the centre frame alone a small shadow's
    // umbra, 0 but for a filter's faint residue. Three frames: the two
    // neighbours agree with each other, and their spread alone cannot tell
    // the umbra from noise.
    std::mt19937 random(13);
    std::normal_distribution<float> gaussian(0.0f, 0.1f);
    const auto in_umbra = [](int x, int y) { return x >= 28 && x < 34 && y >= 20 && y < 26; };
    const std::vector<SyntheticFrame> frames = still_frames(3, [&](int f, int x, int y, float shade) {
        return f == 1 && in_umbra(x, y) ? 1e-7f * float((x + 2 * y) % 3) : shade + gaussian(random);
    });
    const std::vector<float> out = blend(frames, 1, 1);
    double worst = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x)
            if (in_umbra(x, y)) {
                const std::size_t i = std::size_t(y) * kWidth + std::size_t(x);
                worst = std::max(worst, double(std::fabs(out[i] - frames[1].value[i])));
            }
    CHECK(worst == 0);
}

TEST_CASE("temporal window: a camera pan is followed by the motion layer", "[temporal]") {
    // Noise-free, 2 px per frame: the warped neighbours land on whole pixels of the same surface.
    std::vector<SyntheticFrame> still;
    for (int f = 0; f < 5; ++f) still.emplace_back(f, 2.0f, smooth_shade);
    const std::vector<float> out = blend(still, 2, 2);
    double worst = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const std::size_t i = std::size_t(y) * kWidth + std::size_t(x);
            worst = std::max(worst, double(std::fabs(out[i] - still[2].value[i])));
        }
    CHECK(worst < 1e-6);
    // Noisy, the same pan: the noise averages down as on a still camera.
    const std::vector<SyntheticFrame> frames = noisy_frames(2.0f, 0.05f);
    CHECK(mse_from_truth(blend(frames, 2, 2), 2, 2.0f) < 0.3 * mse_from_truth(frames[2].value, 2, 2.0f));
}

TEST_CASE("temporal window: a shadow edge moving over still geometry does not ghost", "[temporal]") {
    // A step that moves 3 px per frame; noise-free, so any difference is a change.
    std::vector<SyntheticFrame> frames;
    for (int f = 0; f < 5; ++f)
        frames.emplace_back(f, 0.0f, [](float world_x, float, int frame) {
            return world_x < 20.0f + 3.0f * float(frame) ? 0.1f : 0.9f;
        });
    const std::vector<float> out = blend(frames, 2, 2);
    CHECK(std::memcmp(out.data(), frames[2].value.data(), out.size() * sizeof(float)) == 0);

    // With noise, the pixels the edge crossed in the window keep their own side's value.
    std::mt19937 random(3);
    std::normal_distribution<float> gaussian(0.0f, 0.02f);
    for (SyntheticFrame &frame : frames)
        for (float &v : frame.value) v += gaussian(random);
    const std::vector<float> noisy = blend(frames, 2, 2);
    double worst_ghost = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 14; x < 32; ++x) {  // the edge sweeps x = 20..32 over the window
            const float truth = float(x) < 26.0f ? 0.1f : 0.9f;
            worst_ghost = std::max(
                worst_ghost, double(std::fabs(noisy[std::size_t(y) * kWidth + std::size_t(x)] - truth)));
        }
    // A ghost is a fraction of the 0.8 step; noise alone stays within a few of its 0.02.
    CHECK(worst_ghost < 0.1);
}

TEST_CASE("temporal window: another object in a neighbour's place is rejected", "[temporal]") {
    std::vector<SyntheticFrame> frames;
    for (int f = 0; f < 3; ++f) frames.emplace_back(0, 0.0f, smooth_shade);
    for (float &v : frames[0].value) v += 0.5f;  // what another object would show
    for (float &v : frames[2].value) v += 0.5f;
    for (float &i : frames[0].id) i = 2;
    for (float &i : frames[2].id) i = 2;
    const std::vector<float> out = blend(frames, 1, 1, 1e6f);  // the shading test all but off
    CHECK(std::memcmp(out.data(), frames[1].value.data(), out.size() * sizeof(float)) == 0);
}

TEST_CASE("temporal window: the same bytes on 1 and 2 threads", "[temporal]") {
    const std::vector<SyntheticFrame> frames = noisy_frames(1.3f, 0.05f);
    std::vector<float> one, two;
    run_with_threads(1, [&] { one = blend(frames, 2, 2); });
    run_with_threads(2, [&] { two = blend(frames, 2, 2); });
    CHECK(std::memcmp(one.data(), two.data(), one.size() * sizeof(float)) == 0);
}

TEST_CASE("temporal history: alpha x frame + (1 - alpha) x the previous output, followed by the motion layer",
          "[temporal]") {
    // The camera pans 2 px a frame; the previous output holds the shade plus 0.1.
    const SyntheticFrame now(1, 2.0f, smooth_shade), before(0, 2.0f, smooth_shade);
    SyntheticFrame history = before;
    for (float &v : history.value) v += 0.1f;
    TemporalWindowSettings settings;
    std::vector<float> out(std::size_t(kWidth) * kHeight);
    blend_temporal_history(now.view(0), history.view(-1), 0.25f, settings,
                           {plane_view(out.data(), kWidth, kHeight)});
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth - 2; ++x) {  // the last 2 columns were off screen before
            const std::size_t i = std::size_t(y) * kWidth + std::size_t(x);
            REQUIRE(out[i] == Approx(now.value[i] + 0.75f * 0.1f).margin(1e-5));
        }
    // Another object where the surface was: the frame's own value.
    for (float &id : history.id) id = 2;
    blend_temporal_history(now.view(0), history.view(-1), 0.25f, settings,
                           {plane_view(out.data(), kWidth, kHeight)});
    CHECK(std::memcmp(out.data(), now.value.data(), out.size() * sizeof(float)) == 0);
    CHECK_THROWS_AS(blend_temporal_history(now.view(0), history.view(-1), 0.0f, settings,
                                           {plane_view(out.data(), kWidth, kHeight)}),
                    Error);
}

TEST_CASE(
    "temporal window extremes: the smallest and largest value at the pixel's surface point over the window",
    "[temporal]") {
    // A camera pan of 2 px a frame: each frame's value is the frame number
    // plus a shade, so the extremes at a surface point are frames -2 and +2.
    std::vector<SyntheticFrame> frames;
    for (int f = 0; f < 5; ++f) {
        frames.emplace_back(f, 2.0f, smooth_shade);
        for (float &v : frames.back().value) v += float(f);
    }
    std::vector<TemporalFrameView> neighbours;
    for (int f = 0; f < 5; ++f)
        if (f != 2) neighbours.push_back(frames[std::size_t(f)].view(f - 2));
    TemporalWindowSettings settings;
    settings.radius_frames = 2;
    std::vector<float> low(std::size_t(kWidth) * kHeight), high(low.size());
    temporal_window_extrema(frames[2].view(0), neighbours, settings, WindowExtreme::Min,
                            {plane_view(low.data(), kWidth, kHeight)});
    temporal_window_extrema(frames[2].view(0), neighbours, settings, WindowExtreme::Max,
                            {plane_view(high.data(), kWidth, kHeight)});
    for (int y = 0; y < kHeight; ++y)
        for (int x = 4; x < kWidth - 4; ++x) {  // the surface points every frame saw
            const std::size_t i = std::size_t(y) * kWidth + std::size_t(x);
            REQUIRE(low[i] == Approx(frames[2].value[i] - 2.0f).margin(1e-5));
            REQUIRE(high[i] == Approx(frames[2].value[i] + 2.0f).margin(1e-5));
        }
    // Another object in the neighbours' place: the frame's own value.
    for (SyntheticFrame &frame : frames)
        if (&frame != &frames[2])
            for (float &id : frame.id) id = 2;
    neighbours.clear();
    for (int f = 0; f < 5; ++f)
        if (f != 2) neighbours.push_back(frames[std::size_t(f)].view(f - 2));
    temporal_window_extrema(frames[2].view(0), neighbours, settings, WindowExtreme::Max,
                            {plane_view(high.data(), kWidth, kHeight)});
    CHECK(std::memcmp(high.data(), frames[2].value.data(), high.size() * sizeof(float)) == 0);
}
