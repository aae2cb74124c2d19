// ISG (Robison and Shirley 2009): the shared formulas against hand-computed
// values, the sample sets' promises, and the soft-shadow filter's penumbra
// against ISG Eq. 8 on a synthetic receiver, and the vectorised loops'
// bits for any thread count and instruction set.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <hwy/targets.h>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/framework/filter_aovs.h"
#include "aaf/core/framework/method_registry.h"
#include "aaf/core/methods/isg/isg_formulas.h"
#include "aaf/core/methods/isg/isg_roles.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/thread_count.h"
#include "methods/isg/isg_shadow.h"

using namespace aaf;
using namespace aaf::isg;

TEST_CASE("ISG sample sets: k x k taps, the centre first, inside the disc or the light's rectangle",
          "[isg]") {
    for (int count : {1, 9, 25, 49, 81})
        for (TapPattern pattern : {TapPattern::Grid, TapPattern::Stratified}) {
            INFO(count << (pattern == TapPattern::Grid ? " grid" : " stratified"));
            const std::vector<Tap> disk = tap_set(count, TapShape::Disk, pattern);
            REQUIRE(int(disk.size()) == count);
            CHECK(disk[0].x == 0.0f);
            CHECK(disk[0].y == 0.0f);
            for (const Tap &t : disk) CHECK(t.x * t.x + t.y * t.y <= 1.0f + 1e-6f);
            // Only the centre sits at the centre (no tap is sampled twice there).
            CHECK(std::count_if(disk.begin(), disk.end(), [](Tap t) { return t.x == 0 && t.y == 0; }) == 1);
            const std::vector<Tap> rect = tap_set(count, TapShape::Rectangle, pattern, 2.0f, 1.0f);
            for (const Tap &t : rect) {
                CHECK(std::fabs(t.x) <= 1.0f);
                CHECK(std::fabs(t.y) <= 0.5f);  // half-height over the larger half-side
            }
        }
    // The regular grid through the concentric map is symmetric: its mean is the centre.
    const std::vector<Tap> grid = tap_set(49, TapShape::Disk, TapPattern::Grid);
    double mx = 0, my = 0;
    for (const Tap &t : grid) {
        mx += t.x;
        my += t.y;
    }
    CHECK(std::fabs(mx) < 1e-5);
    CHECK(std::fabs(my) < 1e-5);
    CHECK_THROWS_AS(tap_set(16, TapShape::Disk, TapPattern::Grid), Error);  // even side: no centre tap
    CHECK_THROWS_AS(tap_set(10, TapShape::Disk, TapPattern::Grid), Error);
}

TEST_CASE("ISG formulas: ISG Eq. 8, 9, 13 and 15 against hand-computed values", "[isg]") {
    // ISG Eq. 8: L d / (D - d) = 0.5 * 1 / (3 - 1).
    CHECK(penumbra_radius_m(0.5f, 1.0f, 3.0f) == Approx(0.25f));
    CHECK(penumbra_radius_m(0.5f, 0.0f, 3.0f) == 0.0f);  // contact: a hard shadow
    CHECK(std::isinf(penumbra_radius_m(0.5f, 3.0f, 3.0f)));
    // ISG Eq. 9: 0.25 m at 5 m with a 1000 px focal length.
    CHECK(screen_radius_px(0.25f, 5.0f, 1000.0f) == Approx(50.0f));
    // ISG Eq. 13: tan(alpha) = E tan(theta) / (e + E); E = 3, e = 1, theta = 45 degrees: atan(0.75).
    CHECK(glossy_gather_angle(0.785398163f, 1.0f, 3.0f) == Approx(std::atan(0.75f)));
    CHECK(glossy_gather_angle(0.1f, 2.0f, INFINITY) == Approx(0.1f));
    CHECK(glossy_gather_angle(0.1f, 2.0f, 0.0f) == 0.0f);  // contact: a sharp reflection
    // ISG Eq. 15: |z - z_f| / z c_inf.
    CHECK(circle_of_confusion_px(2.0f, 4.0f, 10.0f) == Approx(10.0f));
    CHECK(circle_of_confusion_px(4.0f, 4.0f, 10.0f) == 0.0f);
    CHECK(circle_of_confusion_px(8.0f, 4.0f, 10.0f) == Approx(5.0f));
    CHECK(circle_of_confusion_px(INFINITY, 4.0f, 10.0f) == 10.0f);
    CHECK(smoothstep(1.0f, 0.5f) == Approx(0.5f));
    CHECK(smoothstep(1.0f, -1.0f) == 0.0f);
    CHECK(smoothstep(1.0f, 2.0f) == 1.0f);
}

namespace {

constexpr int kWidth = 240, kHeight = 9;
constexpr float kPixel_m = 0.01f;       // each pixel covers 1 cm of the receiver
constexpr float kDepth_m = 5.0f;        // eye depth of every pixel
constexpr float kLightHeight_m = 4.0f;  // D: the light's distance above the receiver
constexpr float kLightHalf_m = 0.5f;    // L: the light's half-side
// An edge blurred by a uniform disc of radius R rises from 0.1 to 0.9 over
// 2 t R, where the disc's part beyond a chord at distance t R is 0.1:
// (acos t - t sqrt(1 - t^2)) / pi = 0.1 at t = 0.6870.
constexpr float kTenToNinetyPerRadius = 2 * 0.6870f;

/// A flat receiver (y = 0) seen head-on, 1 cm per pixel, whose left half is
/// in a hard shadow cast by an occluder `occluder_m` above it, under a 1 m
/// square light 4 m above the edge.
AovSet shadow_edge(float occluder_m) {
    AovSet aovs(kWidth, kHeight);
    const PlaneView v = aovs.add_channel(role_info(roles::HardVisibility).channels[0]);
    const PlaneView d = aovs.add_channel(role_info(roles::OccluderDistance).channels[0]);
    const PlaneView z = aovs.add_channel(role_info(Role::Depth).channels[0], kDepth_m);
    PlaneView p[3];
    for (int c = 0; c < 3; ++c) p[c] = aovs.add_channel(role_info(Role::Position).channels[std::size_t(c)]);
    for (int c = 0; c < 3; ++c) aovs.add_channel(role_info(Role::Unshadowed).channels[std::size_t(c)], 1.0f);
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const bool shadowed = x < kWidth / 2;
            v(x, y) = shadowed ? 0.0f : 1.0f;
            d(x, y) = shadowed ? occluder_m : 0.0f;
            p[0](x, y) = float(x) * kPixel_m;
            p[1](x, y) = 0;
            p[2](x, y) = float(y) * kPixel_m;
        }
    (void)z;
    const LightPlane light =
        LightPlane::square({kWidth / 2 * kPixel_m, kLightHeight_m, 0}, {0, -1, 0}, 2 * kLightHalf_m);
    write_light_attributes(light, aovs);
    aovs.attributes[attr::kCameraFocalPx] = kDepth_m / kPixel_m;  // 1 px = 1 cm at the receiver
    return aovs;
}

/// Distance in pixels, along the middle row, between where `channel`
/// crosses 0.1 and 0.9 (linear interpolation between pixels).
float rise_width_px(const AovSet &filtered, const std::string &channel) {
    const ConstPlaneView v = filtered.channel(channel);
    auto crossing = [&](float level) {
        for (int x = 1; x < kWidth; ++x)
            if (v(x - 1, kHeight / 2) < level && v(x, kHeight / 2) >= level)
                return float(x - 1) +
                       (level - v(x - 1, kHeight / 2)) / (v(x, kHeight / 2) - v(x - 1, kHeight / 2));
        return -1.0f;
    };
    return crossing(0.9f) - crossing(0.1f);
}

}  // namespace

TEST_CASE("isg-shadow: the penumbra widens with the occluder's height as ISG Eq. 8 predicts", "[isg]") {
    const Method &method = find_method("isg-shadow");
    ParameterSet parameters = method.default_parameters();
    parameters.set("search_samples", std::string("81"));
    parameters.set("gather_samples", std::string("121"));
    parameters.set("light_shape", std::string("disk"));
    // A flat receiver: the range function (a Gaussian in world distance)
    // would cap the width, so it is made flat to measure ISG Eq. 8's geometry.
    parameters.set("sigma", 1e3);
    parameters.set("max_radius", 200.0);
    float previous = 0;
    for (float d_m : {0.25f, 0.5f, 1.0f, 1.5f}) {
        INFO("occluder " << d_m << " m above the receiver");
        const AovSet out = filter_aovs(method, shadow_edge(d_m), ChannelMap{}, parameters);
        const float measured = rise_width_px(out, role_info(Role::FilteredVisibility).channels[0]);
        // ISG Eq. 8 and 9: R_g = L d / (D - d) / z_eye * focal, in pixels (1 cm each).
        const float predicted_radius_px = kLightHalf_m * d_m / (kLightHeight_m - d_m) / kPixel_m;
        CHECK(measured > previous);
        CHECK(measured == Approx(kTenToNinetyPerRadius * predicted_radius_px).epsilon(0.2));
        previous = measured;
    }
}

TEST_CASE("isg-shadow: a fully lit input and a pixel without depth stay as they were", "[isg]") {
    const Method &method = find_method("isg-shadow");
    AovSet lit = shadow_edge(0.5f);
    PlaneView v = lit.channel(role_info(roles::HardVisibility).channels[0]);
    std::fill(v.data, v.data + lit.pixel_count(), 1.0f);
    lit.channel(role_info(Role::Depth).channels[0])(3, 3) = 0;  // the background
    const AovSet out = filter_aovs(method, lit, ChannelMap{}, method.default_parameters());
    const ConstPlaneView filtered = out.channel(role_info(Role::FilteredVisibility).channels[0]);
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) CHECK(filtered(x, y) == 1.0f);
}

namespace {

/// A flat receiver facing the camera, 1 cm per pixel, 5 m from the eye
/// (above its middle), whose reflection map is 0 on the left half and 1 on
/// the right, every reflected object `reflected_m` away, theta_max 0.02 rad.
AovSet reflection_edge(float reflected_m) {
    AovSet aovs(kWidth, kHeight);
    PlaneView p[3], n[3], r[3];
    for (std::size_t c = 0; c < 3; ++c) {
        p[c] = aovs.add_channel(role_info(Role::Position).channels[c]);
        n[c] = aovs.add_channel(role_info(Role::Normal).channels[c], c == 2 ? 1.0f : 0.0f);
        r[c] = aovs.add_channel(role_info(roles::Reflection).channels[c]);
    }
    aovs.add_channel(role_info(roles::ReflectionDistance).channels[0], reflected_m);
    aovs.add_channel(role_info(roles::ThetaMax).channels[0], 0.02f);
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            p[0](x, y) = float(x) * kPixel_m;
            p[1](x, y) = float(y) * kPixel_m;
            for (int c = 0; c < 3; ++c) r[c](x, y) = x < kWidth / 2 ? 0.0f : 1.0f;
        }
    aovs.attributes[attr::kCameraEye] = Vec3{kWidth / 2 * kPixel_m, kHeight / 2 * kPixel_m, kDepth_m};
    aovs.attributes[attr::kCameraFocalPx] = kDepth_m / kPixel_m;
    return aovs;
}

}  // namespace

TEST_CASE(
    "isg-glossy: the reflection blurs more with the reflected object's distance, as ISG Eq. 13-14 predict",
    "[isg]") {
    const Method &method = find_method("isg-glossy");
    ParameterSet parameters = method.default_parameters();
    parameters.set("search_samples", std::string("81"));
    parameters.set("gather_samples", std::string("121"));
    parameters.set("sigma", 1e3);  // a flat receiver: measure the geometry, not the range function
    const float focal_px = kDepth_m / kPixel_m;
    const float px_per_rad = float(kHeight) / (2 * std::atan(0.5f * float(kHeight) / focal_px));
    float previous = 0;
    for (float reflected_m : {1.0f, 3.0f, 10.0f, 40.0f}) {
        INFO("reflected object " << reflected_m << " m away");
        const AovSet out = filter_aovs(method, reflection_edge(reflected_m), ChannelMap{}, parameters);
        const float measured = rise_width_px(out, role_info(roles::GlossyReflection).channels[0]);
        // ISG Eq. 13 with e = 5 m; ISG Eq. 14 with cos(theta_incident) = 1 at the edge, seen head-on.
        const float alpha = std::atan(reflected_m * std::tan(0.02f) / (kDepth_m + reflected_m));
        CHECK(measured > previous);
        CHECK(measured == Approx(kTenToNinetyPerRadius * alpha * px_per_rad).epsilon(0.2));
        previous = measured;
    }
    // theta_max = 0 (not glossy): the mirror reflection stays as it was.
    AovSet mirror = reflection_edge(3.0f);
    PlaneView theta = mirror.channel(role_info(roles::ThetaMax).channels[0]);
    std::fill(theta.data, theta.data + mirror.pixel_count(), 0.0f);
    const AovSet out = filter_aovs(method, mirror, ChannelMap{}, parameters);
    CHECK(out.plane(out.index_of("isg_glossy.R")) == mirror.plane(mirror.index_of("reflect.R")));
}

namespace {

/// A pinhole image, 0 on the left half and 1 on the right, every pixel at depth `depth_m`.
AovSet pinhole_edge(float depth_m) {
    AovSet aovs(kWidth, kHeight);
    for (std::size_t c = 0; c < 3; ++c) {
        const PlaneView v = aovs.add_channel(role_info(roles::PinholeBeauty).channels[c]);
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) v(x, y) = x < kWidth / 2 ? 0.0f : 1.0f;
    }
    aovs.add_channel(role_info(Role::Depth).channels[0], depth_m);
    aovs.attributes[attr::kCameraFocalPx] = 500.0f;
    aovs.attributes[attr::kApertureRadius] = 0.1f;
    aovs.attributes[attr::kFocusDistance] = 5.0f;
    return aovs;
}

}  // namespace

TEST_CASE("isg-dof: in focus stays sharp, and a surface blurs by its circle of confusion (ISG Eq. 15)",
          "[isg]") {
    const Method &method = find_method("isg-dof");
    ParameterSet parameters = method.default_parameters();
    parameters.set("search_samples", std::string("81"));
    parameters.set("gather_samples", std::string("121"));
    const AovSet focused = pinhole_edge(5.0f);
    const AovSet sharp = filter_aovs(method, focused, ChannelMap{}, parameters);
    CHECK(sharp.plane(sharp.index_of("isg_dof.G")) == focused.plane(focused.index_of("pinhole.G")));
    const float coc_inf_px = 0.1f / 5.0f * 500.0f;  // aperture / focus distance x focal length
    float previous = 0;
    for (float depth_m : {7.0f, 10.0f, 20.0f}) {
        INFO("depth " << depth_m << " m, focus 5 m");
        const AovSet out = filter_aovs(method, pinhole_edge(depth_m), ChannelMap{}, parameters);
        const float measured = rise_width_px(out, "isg_dof.G");
        const float coc_px = (depth_m - 5.0f) / depth_m * coc_inf_px;  // ISG Eq. 15
        CHECK(measured > previous);
        CHECK(measured == Approx(kTenToNinetyPerRadius * coc_px).epsilon(0.2));
        previous = measured;
    }
}

namespace {

/// Every output channel of `filtered` has the bits of `reference`'s.
void check_same_bits(const AovSet &filtered, const AovSet &reference) {
    REQUIRE(filtered.channel_names() == reference.channel_names());
    for (const std::string &name : reference.channel_names()) {
        const ConstPlaneView a = filtered.channel(name), b = reference.channel(name);
        int differing = 0;
        for (int y = 0; y < a.height; ++y)
            for (int x = 0; x < a.width; ++x)
                differing += std::memcmp(&a(x, y), &b(x, y), sizeof(float)) != 0;
        INFO("channel " << name);
        CHECK(differing == 0);
    }
}

}  // namespace

TEST_CASE("ISG methods: the same bits for any thread count and every instruction set", "[isg]") {
    struct Case {
        const char *method;
        AovSet input;
    };
    const Case cases[] = {{"isg-shadow", shadow_edge(0.5f)},
                          {"isg-glossy", reflection_edge(3.0f)},
                          {"isg-dof", pinhole_edge(2.0f)}};
    for (const Case &c : cases) {
        const Method &method = find_method(c.method);
        const ParameterSet parameters = method.default_parameters();
        std::optional<AovSet> reference;
        // The rows are vectorised with runtime dispatch: every instruction set
        // of the build, its range weights' exponential unfused on all of them.
        for (const std::int64_t target : hwy::SupportedAndGeneratedTargets())
            for (const int threads : {1, 2, 3}) {
                hwy::SetSupportedTargetsForTest(target);
                AovSet out;
                run_with_threads(threads,
                                 [&] { out = filter_aovs(method, c.input, ChannelMap{}, parameters); });
                INFO(c.method << ", target " << hwy::TargetName(target) << ", " << threads << " threads");
                if (!reference)
                    reference = std::move(out);
                else
                    check_same_bits(out, *reference);
            }
        hwy::SetSupportedTargetsForTest(0);
    }
}

namespace {

/// Hard visibility with every case isg-shadow's shortcuts must see through:
/// wide lit and dark areas, a shadow edge, a dark disc, salt and pepper,
/// values other than 0 and 1 (-0, 0.5, NaN, infinity), occluder distances
/// out of range, a pixel without depth and one without position.
AovSet varied_shadows() {
    AovSet aovs = shadow_edge(0.5f);
    PlaneView v = aovs.channel(role_info(roles::HardVisibility).channels[0]);
    PlaneView d = aovs.channel(role_info(roles::OccluderDistance).channels[0]);
    PlaneView z = aovs.channel(role_info(Role::Depth).channels[0]);
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const float dx = float(x - 190), dy = float(y - 4);
            if (dx * dx + dy * dy < 12) {
                v(x, y) = 0;
                d(x, y) = 0.3f;
            }
            if (x >= 150 && x < 170 && (x * 7 + y * 3) % 5 == 0) {
                v(x, y) = 0;
                d(x, y) = 0.8f;
            }
            z(x, y) = kDepth_m * (1.0f + 0.002f * float(x % 13));
        }
    v(20, 2) = -0.0f;
    v(60, 5) = 0.5f;
    v(130, 1) = std::numeric_limits<float>::quiet_NaN();
    v(140, 6) = std::numeric_limits<float>::infinity();
    v(210, 3) = 0.25f;
    d(40, 4) = std::numeric_limits<float>::infinity();
    d(100, 7) = -1.0f;
    z(90, 0) = 0;
    aovs.channel(role_info(Role::Position).channels[0])(180, 8) = std::numeric_limits<float>::quiet_NaN();
    return aovs;
}

}  // namespace

TEST_CASE("isg-shadow: passing over the blocks whose result is known gives the bits of computing them",
          "[isg]") {
    const AovSet aovs = varied_shadows();
    ShadowInputs in;
    in.hard = aovs.channel(role_info(roles::HardVisibility).channels[0]);
    in.occluder_m = aovs.channel(role_info(roles::OccluderDistance).channels[0]);
    in.depth_m = aovs.channel(role_info(Role::Depth).channels[0]);
    for (std::size_t c = 0; c < 3; ++c)
        in.position.c[c] = aovs.channel(role_info(Role::Position).channels[c]);
    const LightPlane light = read_light_attributes(aovs);
    const float focal_px = kDepth_m / kPixel_m;
    std::vector<float> full(aovs.pixel_count()), passed(aovs.pixel_count());
    std::size_t compared = 0, changed = 0;
    for (const std::int64_t target : hwy::SupportedAndGeneratedTargets())
        for (TapShape shape : {TapShape::Rectangle, TapShape::Disk})
            for (TapPattern pattern : {TapPattern::Grid, TapPattern::Stratified})
                for (int samples : {9, 49, 121})
                    for (float max_radius_px : {3.0f, 64.0f}) {
                        hwy::SetSupportedTargetsForTest(target);
                        IsgShadowSettings settings;
                        settings.light_shape = shape;
                        settings.pattern = pattern;
                        settings.search_samples = samples;
                        settings.gather_samples = 130 - samples;
                        settings.max_radius_px = max_radius_px;
                        settings.sigma = 1.0f;
                        settings.pass_over_uniform = false;
                        isg_shadow_visibility(in, settings, light, focal_px,
                                              plane_view(full.data(), kWidth, kHeight));
                        settings.pass_over_uniform = true;
                        isg_shadow_visibility(in, settings, light, focal_px,
                                              plane_view(passed.data(), kWidth, kHeight));
                        INFO(hwy::TargetName(target)
                             << ", " << samples << " search taps, max radius " << max_radius_px);
                        REQUIRE(std::memcmp(full.data(), passed.data(), full.size() * sizeof(float)) == 0);
                        for (std::size_t i = 0; i < full.size(); ++i) {
                            compared += 1;
                            const float hard = in.hard.data[i];
                            changed += std::memcmp(&full[i], &hard, sizeof hard) != 0;
                        }
                    }
    hwy::SetSupportedTargetsForTest(0);
    // The input is one the filter changes, not only passes through.
    CHECK(changed > compared / 20);
}
