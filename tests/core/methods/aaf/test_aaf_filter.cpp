#include <catch2/catch.hpp>

#include <tbb/task_arena.h>
#include <cmath>
#include <random>
#include <vector>

#include "aaf/core/kernels/light_bandlimit.h"
#include "aaf/core/methods/aaf/aaf_bandlimits.h"
#include "aaf/core/methods/aaf/aaf_filter.h"
#include "aaf/core/util/error.h"

using namespace aaf;

namespace {

/// A flat receiver at y = 0 seen straight from above: pixel (x, y) sits at
/// world (x, 0, y) * spacing, under a light at height 2 m facing down.
struct FlatScene {
    int width, height;
    float spacing_m = 0.01f;
    std::vector<float> visibility, d1, d2_min, d2_max, object_id, pixel_size;
    std::vector<float> px, py, pz, nx, ny, nz;
    LightPlane light = LightPlane::square({0, 2, 0}, {0, -1, 0}, 1.0f);

    FlatScene(int w, int h, float d2_m) : width(w), height(h) {
        const std::size_t n = std::size_t(w) * h;
        visibility.assign(n, 1.0f);
        d1.assign(n, 2.0f);
        d2_min.assign(n, d2_m);
        d2_max.assign(n, d2_m);
        object_id.assign(n, 1.0f);
        pixel_size.assign(n, spacing_m);
        px.resize(n);
        py.assign(n, 0.0f);
        pz.resize(n);
        nx.assign(n, 0.0f);
        ny.assign(n, 1.0f);
        nz.assign(n, 0.0f);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                px[index(x, y)] = x * spacing_m;
                pz[index(x, y)] = y * spacing_m;
            }
    }
    std::size_t index(int x, int y) const { return std::size_t(y) * width + x; }
    ConstPlaneView view(const std::vector<float> &v) const { return plane_view(v.data(), width, height); }

    AafInputs inputs() const {
        AafInputs in;
        in.visibility = view(visibility);
        in.d1 = view(d1);
        in.d2_min = view(d2_min);
        in.d2_max = view(d2_max);
        in.position = {view(px), view(py), view(pz)};
        in.normal = {view(nx), view(ny), view(nz)};
        in.object_id = view(object_id);
        in.pixel_size = view(pixel_size);
        return in;
    }

    void fill_noise(unsigned seed) {
        std::mt19937 rng(seed);
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        for (float &v : visibility) v = u(rng);
    }

    std::vector<float> run(const AafParams &params, std::vector<float> *beta = nullptr) const {
        std::vector<float> out(visibility.size(), -1.0f), beta_out(visibility.size(), -1.0f);
        AafOutputs outputs{plane_view(out.data(), width, height), plane_view(beta_out.data(), width, height)};
        aaf_filter(inputs(), light, params, outputs);
        if (beta) *beta = beta_out;
        return out;
    }
};

/// Two pixels under the light at (0, 2, 0) facing down: the centre at (1, 0,
/// 0) and a tap 0.5 m above it.
FlatScene centre_and_tap_above() {
    FlatScene pair(2, 1, 1.0f);
    pair.px = {1.0f, 1.0f};
    pair.py = {0.0f, 0.5f};
    pair.pz = {0.0f, 0.0f};
    return pair;
}

}  // namespace

TEST_CASE("Separable AAF equals the brute-force 2D Gaussian when beta is constant", "[aaf][filter]") {
    FlatScene scene(40, 30, 1.0f);  // s2 = 1: beta = sigma s2 / (k mu) = 0.5 / 6 m
    scene.fill_noise(7);
    AafParams params;
    params.max_radius_px = 12;
    params.light_bandlimit = LightBandlimit::Sigma;  // Omega_L = 1/sigma: beta as hand-computed
    params.symmetric_borders = false;                // the window the brute force below sums
    std::vector<float> beta;
    const std::vector<float> separable = scene.run(params, &beta);

    const float expected_beta = 0.5f / 6.0f;
    const int radius = std::min(params.max_radius_px, int(std::ceil(3 * expected_beta / scene.spacing_m)));
    REQUIRE(radius == 12);
    double max_diff = 0;
    for (int y = 0; y < scene.height; ++y)
        for (int x = 0; x < scene.width; ++x) {
            REQUIRE(beta[scene.index(x, y)] == Approx(expected_beta));
            // AAF Eq. 10-12 evaluated directly over the square window of the separable passes.
            double sum = 0, weight_sum = 0;
            for (int ty = std::max(0, y - radius); ty <= std::min(scene.height - 1, y + radius); ++ty)
                for (int tx = std::max(0, x - radius); tx <= std::min(scene.width - 1, x + radius); ++tx) {
                    const double dx = (tx - x) * scene.spacing_m, dz = (ty - y) * scene.spacing_m;
                    const double w = std::exp(-(dx * dx + dz * dz) / (2.0 * expected_beta * expected_beta));
                    sum += w * scene.visibility[scene.index(tx, ty)];
                    weight_sum += w;
                }
            max_diff = std::max(max_diff, std::abs(sum / weight_sum - separable[scene.index(x, y)]));
        }
    CHECK(max_diff < 2e-6);

    // The library's exact 2D mode agrees as well.
    params.mode = AafFilterMode::Exact2D;
    const std::vector<float> exact = scene.run(params);
    for (std::size_t i = 0; i < exact.size(); ++i) REQUIRE(exact[i] == Approx(separable[i]).margin(2e-6));
}

TEST_CASE("A fully lit region passes through unchanged", "[aaf][filter]") {
    FlatScene scene(32, 16, 1.0f);
    // Left half: penumbra with occluders and noisy visibility; right half: lit, no occluder.
    scene.fill_noise(3);
    for (int y = 0; y < scene.height; ++y)
        for (int x = 16; x < scene.width; ++x) {
            scene.visibility[scene.index(x, y)] = 1.0f;
            scene.d2_min[scene.index(x, y)] = scene.d2_max[scene.index(x, y)] = 0.0f;
        }
    std::vector<float> beta;
    const std::vector<float> out = scene.run(AafParams{}, &beta);
    // Beyond the 5-pixel fill radius nothing is borrowed: not filtered, value kept exactly.
    for (int y = 0; y < scene.height; ++y)
        for (int x = 21; x < scene.width; ++x) {
            CHECK(beta[scene.index(x, y)] == 0.0f);
            CHECK(out[scene.index(x, y)] == 1.0f);
        }
    // Occluders everywhere, yet every sample unoccluded: filtered, and still exactly 1.
    FlatScene lit(24, 24, 1.0f);
    std::vector<float> lit_beta;
    const std::vector<float> lit_out = lit.run(AafParams{}, &lit_beta);
    CHECK(lit_beta[lit.index(12, 12)] > 0.0f);
    for (float v : lit_out) REQUIRE(v == 1.0f);
}

TEST_CASE("Unoccluded pixels borrow occluder distances within the fill radius only", "[aaf][filter]") {
    FlatScene scene(30, 1, 1.0f);
    for (int x = 1; x < scene.width; ++x) scene.d2_min[x] = scene.d2_max[x] = 0.0f;  // only x = 0 occluded
    std::vector<float> beta;
    scene.run(AafParams{}, &beta);
    const float sigma_m = light_bandlimit_sigma_m(scene.light, AafParams{}.light_bandlimit);
    const float expected = aaf_bandlimits(2.0f, 1.0f, 1.0f, 0.01f, sigma_m, AafParams{}).beta_m;
    for (int x = 0; x <= 5; ++x) CHECK(beta[x] == Approx(expected));
    for (int x = 6; x < scene.width; ++x) CHECK(beta[x] == 0.0f);
}

// Issue 19: a window cut by the image edge on one side only averages the
// interior's values, so on a shadow gradient the border pixels came out
// biased (by up to 0.064 on a render), worse than leaving them unfiltered.
TEST_CASE("On a shadow gradient the 10 px border strip is no worse filtered than unfiltered",
          "[aaf][filter][borders]") {
    FlatScene scene(64, 48, 1.0f);  // s2 = 1: a wide filter, about 5 px beta, 15 px reach
    std::vector<float> truth(scene.visibility.size());
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> noise(-0.02f, 0.02f);  // a high-spp render's noise, 0.012 rms
    for (int y = 0; y < scene.height; ++y)
        for (int x = 0; x < scene.width; ++x) {
            const std::size_t i = scene.index(x, y);
            truth[i] = 0.05f + 0.9f * float(x + y) / float(scene.width + scene.height - 2);
            scene.visibility[i] = truth[i] + noise(rng);
        }
    auto border_rmse = [&](const std::vector<float> &image) {
        double sum = 0;
        int count = 0;
        for (int y = 0; y < scene.height; ++y)
            for (int x = 0; x < scene.width; ++x)
                if (std::min({x, y, scene.width - 1 - x, scene.height - 1 - y}) < 10) {
                    const double e = image[scene.index(x, y)] - truth[scene.index(x, y)];
                    sum += e * e;
                    ++count;
                }
        return std::sqrt(sum / count);
    };
    const double unfiltered = border_rmse(scene.visibility);
    for (const AafFilterMode mode : {AafFilterMode::Separable, AafFilterMode::Exact2D}) {
        AafParams params;
        params.mode = mode;
        std::vector<float> beta;
        const double symmetric = border_rmse(scene.run(params, &beta));
        REQUIRE(beta[scene.index(32, 24)] / scene.spacing_m > 4.0f);
        params.symmetric_borders = false;
        const double one_sided = border_rmse(scene.run(params));
        INFO("mode " << int(mode) << ": border RMSE unfiltered " << unfiltered << ", symmetric " << symmetric
                     << ", one-sided " << one_sided);
        CHECK(symmetric <= unfiltered);
        CHECK(one_sided > unfiltered);  // the bias this guards against
    }
}

// --light-distance ray slides a tap along the direction to the light onto the
// centre's plane parallel to the light: on such a plane nothing slides, and
// it equals AAF Eq. 12; on a receiver tilted towards the light it differs.
TEST_CASE("Distances along the ray equal AAF Eq. 12 on a receiver parallel to the light", "[aaf][filter]") {
    FlatScene scene(40, 30, 1.0f);
    scene.fill_noise(9);
    AafParams params;
    params.light_distance = AafLightDistance::AlongLightDirection;
    const std::vector<float> along_ray = scene.run(params);
    params.light_distance = AafLightDistance::OrthogonalProjection;
    CHECK(along_ray == scene.run(params));
    // Hand value: light centre (0, 2, 0) facing down, centre pixel at (1, 0, 0), tap 0.5 m above
    // it. AAF Eq. 12 drops the vertical offset (distance 0); sliding the tap along l = (-1, 2, 0) / sqrt 5
    // onto the centre's plane y = 0 moves it to (1.25, 0, 0): du = 0.25 m.
    FlatScene pair = centre_and_tap_above();
    params.light_distance = AafLightDistance::AlongLightDirection;
    const GatherGuides guides = aaf_gather_guides(pair.inputs(), pair.light, params);
    REQUIRE(guides.sheared());
    const float du = guides.coord_u_m[1] - guides.coord_u_m[0] -
                     guides.shear_u[0] * (guides.coord_n_m[1] - guides.coord_n_m[0]);
    const float dv = guides.coord_v_m[1] - guides.coord_v_m[0] -
                     guides.shear_v[0] * (guides.coord_n_m[1] - guides.coord_n_m[0]);
    CHECK(std::fabs(du) == Approx(0.25f));
    CHECK(dv == Approx(0.0f).margin(1e-6));
    params.light_distance = AafLightDistance::OrthogonalProjection;
    CHECK(!aaf_gather_guides(pair.inputs(), pair.light, params).sheared());
}

// The slide is along the ray to the light's centre; towards another light
// point y it differs by (y - c) / d1 per metre along the light's normal, so
// over the light the squared offset grows by dn^2 var(y) / d1^2 per axis.
TEST_CASE("Distances along the ray add the light's spread of directions", "[aaf][filter]") {
    // Hand values: a square of side 1, sigma 0.5, truncated at t = h / sigma = 1:
    // var = sigma^2 (1 - 2 phi(1) / erf(1 / sqrt 2)) = 0.25 (1 - 2 x 0.2419707 / 0.6826895) = 0.0727813.
    const LightPlane square = LightPlane::square({0, 2, 0}, {0, -1, 0}, 1.0f);
    CHECK(square.variance_u_m2() == Approx(0.0727813).epsilon(1e-5));
    CHECK(square.variance_v_m2() == Approx(0.0727813).epsilon(1e-5));
    LightPlane uniform = square;
    uniform.profile = LightProfile::Uniform;
    uniform.height_m = 0.6f;
    CHECK(uniform.variance_u_m2() == Approx(0.25 / 3));
    CHECK(uniform.variance_v_m2() == Approx(0.09 / 3));
    LightPlane wide = square;  // untruncated in float: the Gaussian's own variance
    wide.width_m = 20.0f;
    CHECK(wide.variance_u_m2() == Approx(0.25).epsilon(1e-5));

    // Centre pixel at (1, 0, 0), d1 = 2 m below the light: 1 / (2 sigma_n^2) =
    // (var_u + var_v) / d1^2 times the isotropic 1 / (2 beta^2).
    FlatScene pair = centre_and_tap_above();
    AafParams params;
    params.light_distance = AafLightDistance::AlongLightDirection;
    const GatherGuides guides = aaf_gather_guides(pair.inputs(), pair.light, params);
    REQUIRE(guides.sheared());
    REQUIRE(guides.inv_two_sigma_sq[0] > 0);
    CHECK(guides.inv_two_sigma_sq_n[0] ==
          Approx(2 * 0.0727813 / 4 * guides.inv_two_sigma_sq[0]).epsilon(1e-5));
    // Where the projection holds (guarded, a floor under the light) nothing slides and nothing spreads.
    params.light_distance = AafLightDistance::Guarded;
    CHECK(aaf_gather_guides(pair.inputs(), pair.light, params).inv_two_sigma_sq_n[0] == 0.0f);
}

TEST_CASE("Taps of other objects and turned normals are rejected", "[aaf][filter]") {
    FlatScene scene(20, 20, 1.0f);
    for (int y = 0; y < scene.height; ++y)
        for (int x = 0; x < scene.width; ++x) {
            const bool left = x < 10;
            scene.visibility[scene.index(x, y)] = left ? 0.2f : 0.9f;
            // Left and right differ by object id in the top half, by normal in the bottom half.
            if (y < 10)
                scene.object_id[scene.index(x, y)] = left ? 1.0f : 2.0f;
            else if (!left) {
                scene.nx[scene.index(x, y)] = 1.0f;
                scene.ny[scene.index(x, y)] = 0.0f;
            }
        }
    const std::vector<float> out = scene.run(AafParams{});
    for (int y = 0; y < scene.height; ++y)
        for (int x = 0; x < scene.width; ++x) CHECK(out[scene.index(x, y)] == Approx(x < 10 ? 0.2f : 0.9f));
}

TEST_CASE("A NaN or zero normal never rejects the centre tap", "[aaf][filter]") {
    FlatScene scene(9, 9, 1.0f);
    scene.fill_noise(11);
    const std::size_t centre = scene.index(4, 4);
    scene.nx[centre] = std::nanf("");
    scene.ny[centre] = 0.0f;
    const std::vector<float> out = scene.run(AafParams{});
    CHECK(out[centre] == scene.visibility[centre]);
    for (float v : out) CHECK(std::isfinite(v));
}

TEST_CASE("AAF output does not depend on the thread count", "[aaf][filter]") {
    FlatScene scene(64, 48, 0.8f);
    scene.fill_noise(5);
    for (int i = 0; i < 64 * 48; i += 7) scene.d2_max[i] = 0.0f;
    std::vector<float> one, four;
    tbb::task_arena(1).execute([&] { one = scene.run(AafParams{}); });
    tbb::task_arena(4).execute([&] { four = scene.run(AafParams{}); });
    CHECK(one == four);
}

TEST_CASE("AAF rejects mismatched inputs and bad parameters", "[aaf][filter]") {
    FlatScene scene(8, 8, 1.0f);
    AafParams bad;
    bad.alpha = 1.5f;
    CHECK_THROWS_AS(scene.run(bad), Error);
    AafInputs in = scene.inputs();
    in.d1.width = 7;
    std::vector<float> out(64);
    CHECK_THROWS_WITH(aaf_filter(in, scene.light, AafParams{}, {plane_view(out.data(), 8, 8), {}}),
                      Catch::Contains("d1"));
}

TEST_CASE("Guarded distances: AAF Eq. 12 where the projection holds, along the ray where it collapses a wall",
          "[aaf][filter]") {
    // The pair of the test above: centre at (1, 0, 0), tap 0.5 m above it, light facing down.
    FlatScene pair = centre_and_tap_above();
    AafParams params;
    params.light_distance = AafLightDistance::Guarded;
    auto tap_du = [&](const GatherGuides &g) {
        return g.coord_u_m[1] - g.coord_u_m[0] - g.shear_u[0] * (g.coord_n_m[1] - g.coord_n_m[0]);
    };
    // A floor (normal parallel to the light's): AAF Eq. 12, the vertical offset dropped.
    GatherGuides floor = aaf_gather_guides(pair.inputs(), pair.light, params);
    REQUIRE(floor.sheared());
    CHECK(tap_du(floor) == 0.0f);
    // A wall (normal +x, perpendicular to the light's): Eq. 12 would put both
    // points at one spot; along the ray the tap is 0.25 m away, as above.
    pair.nx = {1.0f, 1.0f};
    pair.ny = {0.0f, 0.0f};
    CHECK(std::fabs(tap_du(aaf_gather_guides(pair.inputs(), pair.light, params))) == Approx(0.25f));
    params.light_distance = AafLightDistance::OrthogonalProjection;
    CHECK(!aaf_gather_guides(pair.inputs(), pair.light, params).sheared());
}

TEST_CASE("The pixel footprint in the light plane's units shrinks by the planes' cosine, down to 0.1",
          "[aaf][bandlimits]") {
    const Vec3 down{0, -1, 0};
    CHECK(projected_pixel_size_m(0.01f, {0, 1, 0}, down) == Approx(0.01f));
    CHECK(projected_pixel_size_m(0.01f, {0, 2, 0}, down) == Approx(0.01f));  // any length
    CHECK(projected_pixel_size_m(0.01f, {std::sqrt(3.0f) / 2, 0.5f, 0}, down) == Approx(0.005f));
    CHECK(projected_pixel_size_m(0.01f, {1, 0, 0}, down) == Approx(0.01f * kDegenerateProjectionCos));
    CHECK(projected_pixel_size_m(0.01f, {0, 0, 0}, down) == 0.01f);
    // A smaller footprint raises the pixel band-limit (AAF Eq. 6): beta where it clips shrinks.
    AafParams params;
    const float beta_receiver = aaf_bandlimits(2.0f, 1.999f, 1.999f, 0.01f, 0.3f, params).beta_m;
    const float beta_projected = aaf_bandlimits(2.0f, 1.999f, 1.999f, 0.005f, 0.3f, params).beta_m;
    CHECK(beta_projected == Approx(beta_receiver / 2).epsilon(1e-3));
}
