// The shared world-space gather (gather.h): what every method's filter relies on.
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "aaf/core/kernels/gather.h"
#include "aaf/core/util/error.h"

using namespace aaf;

namespace {

/// A flat plane seen from above: pixel (x, y) at (x, y) * spacing metres,
/// normal +z, one object, one Gaussian width and radius everywhere.
GatherGuides flat_guides(int width, int height, float spacing_m, float sigma_m, int radius_px) {
    GatherGuides g;
    g.resize(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::size_t i = g.index(x, y);
            g.coord_u_m[i] = x * spacing_m;
            g.coord_v_m[i] = y * spacing_m;
            g.normal_z[i] = 1.0f;
            g.object_id[i] = 1.0f;
            g.inv_two_sigma_sq[i] = 1.0f / (2.0f * sigma_m * sigma_m);
            g.radius_px[i] = radius_px;
        }
    return g;
}

std::vector<float> noise(std::size_t count, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<float> v(count);
    for (float &x : v) x = u(rng);
    return v;
}

bool same_bytes(const std::vector<float> &a, const std::vector<float> &b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

}  // namespace

TEST_CASE("Gather: K channels in one pass equal K single-channel passes, bit for bit", "[gather]") {
    const int w = 23, h = 17;
    const GatherGuides g = flat_guides(w, h, 0.01f, 0.02f, 6);
    for (GatherMode mode : {GatherMode::Separable, GatherMode::Full2D}) {
        GatherSettings settings;
        settings.mode = mode;
        std::vector<std::vector<float>> sources, together(5, std::vector<float>(w * h));
        for (unsigned k = 0; k < 5; ++k) sources.push_back(noise(w * h, k));
        std::vector<ConstPlaneView> in;
        std::vector<PlaneView> out;
        for (unsigned k = 0; k < 5; ++k) {
            in.push_back(plane_view(sources[k].data(), w, h));
            out.push_back(plane_view(together[k].data(), w, h));
        }
        gather(g, settings, in, out);  // 5 channels: one sweep of 4, one of 1
        for (unsigned k = 0; k < 5; ++k) {
            std::vector<float> alone(w * h);
            gather(g, settings, {in[k]}, {plane_view(alone.data(), w, h)});
            CHECK(same_bytes(alone, together[k]));
        }
    }
}

TEST_CASE("Gather: a constant stays constant and a pixel of radius 0 keeps its value", "[gather]") {
    const int w = 19, h = 13;
    GatherGuides g = flat_guides(w, h, 0.01f, 0.015f, 5);
    g.radius_px[g.index(4, 4)] = 0;
    std::vector<float> constant(w * h, 0.625f), out(w * h);
    gather(g, {}, {plane_view(constant.data(), w, h)}, {plane_view(out.data(), w, h)});
    for (float v : out) CHECK(v == Approx(0.625f).epsilon(1e-6));

    std::vector<float> source = noise(w * h, 3);
    gather(g, {}, {plane_view(source.data(), w, h)}, {plane_view(out.data(), w, h)});
    CHECK(out[g.index(4, 4)] == source[g.index(4, 4)]);
}

TEST_CASE("Gather: taps on another object or with a turned normal never contribute", "[gather]") {
    const int w = 20, h = 10;
    GatherGuides g = flat_guides(w, h, 0.01f, 0.05f, 8);
    std::vector<float> source(w * h, 0.0f), out(w * h);
    for (int y = 0; y < h; ++y)
        for (int x = w / 2; x < w; ++x) {
            source[g.index(x, y)] = 1.0f;
            if (y < h / 2)
                g.object_id[g.index(x, y)] = 2.0f;  // top right: another object
            else
                g.normal_z[g.index(x, y)] = -1.0f;  // bottom right: a normal turned 180 degrees
        }
    for (GatherMode mode : {GatherMode::Separable, GatherMode::Full2D}) {
        GatherSettings settings;
        settings.mode = mode;
        gather(g, settings, {plane_view(source.data(), w, h)}, {plane_view(out.data(), w, h)});
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w / 2; ++x) CHECK(out[g.index(x, y)] == 0.0f);
    }
}

TEST_CASE("Gather: the result does not depend on the thread count", "[gather]") {
    const int w = 64, h = 48;
    const GatherGuides g = flat_guides(w, h, 0.01f, 0.03f, 9);
    const std::vector<float> source = noise(w * h, 11);
    const tbb::global_control allow(tbb::global_control::max_allowed_parallelism, 4);
    std::vector<float> one(w * h), three(w * h);
    tbb::task_arena(1).execute(
        [&] { gather(g, {}, {plane_view(source.data(), w, h)}, {plane_view(one.data(), w, h)}); });
    tbb::task_arena(3).execute(
        [&] { gather(g, {}, {plane_view(source.data(), w, h)}, {plane_view(three.data(), w, h)}); });
    CHECK(same_bytes(one, three));
}

TEST_CASE("Modulated gather: without factors it is the 2D gather, with cos/sin it is the hand-summed kernel",
          "[gather]") {
    const int w = 15, h = 11, radius = 4;
    const float spacing = 0.01f, sigma = 0.02f;
    const GatherGuides g = flat_guides(w, h, spacing, sigma, radius);
    const std::vector<float> source = noise(w * h, 5);
    GatherSettings full;
    full.mode = GatherMode::Full2D;
    std::vector<float> plain(w * h), modulated(w * h);
    gather(g, full, {plane_view(source.data(), w, h)}, {plane_view(plain.data(), w, h)});
    gather_modulated(g, full, {plane_view(source.data(), w, h)}, {plane_view(modulated.data(), w, h)}, {}, {},
                     GatherNormalisation::WeightSum);
    // The same weights to rounding: the plain gather's SIMD kernels fuse
    // multiply-adds where the instruction set has them (gather_rows.h), the
    // modulated path is scalar and rounds each product.
    for (std::size_t i = 0; i < plain.size(); ++i) {
        INFO("pixel " << i);
        CHECK(modulated[i] == Approx(plain[i]).margin(1e-6));
    }

    // MAAF's x-side kernel cos(omega_u du) (-sin(omega_v dv)) g(du, dv), unnormalised, at one pixel.
    const std::vector<float> omega_u(w * h, 40.0f), omega_v(w * h, 25.0f);  // radians per metre
    const AxisModulation along_u{AxisModulation::Kind::Cos, plane_view(omega_u.data(), w, h), {}};
    const AxisModulation along_v{AxisModulation::Kind::NegSin, plane_view(omega_v.data(), w, h), {}};
    gather_modulated(g, full, {plane_view(source.data(), w, h)}, {plane_view(modulated.data(), w, h)},
                     along_u, along_v, GatherNormalisation::None);
    const int cx = 7, cy = 5;
    double expected = 0;
    for (int ty = cy - radius; ty <= cy + radius; ++ty)
        for (int tx = cx - radius; tx <= cx + radius; ++tx) {
            const double du = (tx - cx) * double(spacing), dv = (ty - cy) * double(spacing);
            const double weight = std::exp(-(du * du + dv * dv) / (2.0 * sigma * sigma));
            expected += weight * std::cos(40.0 * du) * -std::sin(25.0 * dv) * source[g.index(tx, ty)];
        }
    CHECK(modulated[g.index(cx, cy)] == Approx(expected).margin(1e-5));
}

TEST_CASE("Gather: mismatched sizes and counts are errors", "[gather]") {
    const GatherGuides g = flat_guides(8, 8, 0.01f, 0.02f, 2);
    std::vector<float> a(64), small(16);
    CHECK_THROWS_AS(gather(g, {}, {plane_view(a.data(), 8, 8)}, {}), Error);
    CHECK_THROWS_AS(gather(g, {}, {plane_view(small.data(), 4, 4)}, {plane_view(a.data(), 8, 8)}), Error);
    GatherSettings bad;
    bad.normal_threshold_deg = 200;
    CHECK_THROWS_AS(gather(g, bad, {plane_view(a.data(), 8, 8)}, {plane_view(a.data(), 8, 8)}), Error);
}

TEST_CASE("Gather: with a v width plane a tap weighs exp(-du^2 a_u - dv^2 a_v)", "[gather]") {
    // A unit impulse at the centre of a flat plane: the 2D gather at a
    // neighbour (ox, oy) is its weight towards the impulse over its weight sum.
    const int size = 21, centre = 10;
    const float spacing = 0.01f, sigma_u = 0.03f, sigma_v = 0.012f;
    GatherGuides g = flat_guides(size, size, spacing, sigma_u, 9);
    g.inv_two_sigma_sq_v.assign(std::size_t(size) * size, 1.0f / (2.0f * sigma_v * sigma_v));
    std::vector<float> impulse(std::size_t(size) * size, 0.0f), out(impulse.size());
    impulse[g.index(centre, centre)] = 1.0f;
    GatherSettings settings;
    settings.mode = GatherMode::Full2D;
    gather(g, settings, {plane_view(impulse.data(), size, size)}, {plane_view(out.data(), size, size)});

    auto weight = [&](int ox, int oy) {
        const double du = ox * spacing, dv = oy * spacing;
        return std::exp(-du * du / (2.0 * sigma_u * sigma_u) - dv * dv / (2.0 * sigma_v * sigma_v));
    };
    auto expected = [&](int x, int y) {  // the window of (x, y), cut by nothing at these offsets
        double sum = 0;
        for (int ty = y - 9; ty <= y + 9; ++ty)
            for (int tx = x - 9; tx <= x + 9; ++tx)
                if (tx >= 0 && ty >= 0 && tx < size && ty < size) sum += weight(tx - x, ty - y);
        return weight(centre - x, centre - y) / sum;
    };
    for (auto [ox, oy] : {std::pair{2, 0}, std::pair{0, 2}, std::pair{1, 1}, std::pair{3, -1}})
        CHECK(out[g.index(centre + ox, centre + oy)] ==
              Approx(expected(centre + ox, centre + oy)).epsilon(2e-3));
    // Along u the kernel is wider: at 2 px the weights are 0.80 along u and 0.25 along v.
    CHECK(out[g.index(centre + 2, centre)] > 2.5f * out[g.index(centre, centre + 2)]);

    // The separable passes carry the same widths.
    std::vector<float> separable(impulse.size());
    settings.mode = GatherMode::Separable;
    gather(g, settings, {plane_view(impulse.data(), size, size)}, {plane_view(separable.data(), size, size)});
    for (auto [ox, oy] : {std::pair{2, 0}, std::pair{0, 2}, std::pair{1, 1}})
        CHECK(separable[g.index(centre + ox, centre + oy)] ==
              Approx(out[g.index(centre + ox, centre + oy)]).epsilon(2e-3));

    // A v plane of another size is refused.
    g.inv_two_sigma_sq_v.resize(5);
    CHECK_THROWS_AS(
        gather(g, settings, {plane_view(impulse.data(), size, size)}, {plane_view(out.data(), size, size)}),
        Error);
}
