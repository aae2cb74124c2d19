// The ISG methods on a small render of `gallery`: finite outputs, and each
// effect closer to its distribution-ray-traced reference than the
// single-ray input it starts from (what the study measures at full size).
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "../scratch_dir.h"
#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/framework/filter_aovs.h"
#include "aaf/core/framework/method_registry.h"
#include "aaf/core/methods/isg/isg_roles.h"
#include "aaf/trace/render.h"

using namespace aaf;

namespace {

AovSet render_gallery(const std::string &scene, int spp) {
    trace::RenderSettings settings;
    settings.width = 64;
    settings.height = 48;
    settings.spp = spp;
    settings.aovs = trace::parse_aov_groups("isg,aaf,depth");
    return trace::render_scene(scene, settings);
}

/// RMS difference of `role_a` in `a` and `role_b` in `b` over the pixels where `mask` (if any) is positive.
double rms(const AovSet &a, Role role_a, const AovSet &b, Role role_b, const std::string &mask = "") {
    const std::vector<std::string> &names_a = role_info(role_a).channels,
                                   &names_b = role_info(role_b).channels;
    double sum = 0;
    std::size_t count = 0;
    for (std::size_t c = 0; c < names_a.size(); ++c) {
        const ConstPlaneView va = a.channel(names_a[c]), vb = b.channel(names_b[c]);
        for (int y = 0; y < a.height(); ++y)
            for (int x = 0; x < a.width(); ++x) {
                if (!mask.empty() && !(a.channel(mask)(x, y) > 0)) continue;
                sum += double(va(x, y) - vb(x, y)) * double(va(x, y) - vb(x, y));
                ++count;
            }
    }
    return std::sqrt(sum / double(count));
}

bool all_finite(const AovSet &aovs, Role role) {
    for (const std::string &name : role_info(role).channels) {
        const ConstPlaneView v = aovs.channel(name);
        for (int y = 0; y < aovs.height(); ++y)
            for (int x = 0; x < aovs.width(); ++x)
                if (!std::isfinite(v(x, y))) return false;
    }
    return true;
}

AovSet run(const char *name, const AovSet &input) {
    const Method &method = find_method(name);
    return filter_aovs(method, input, ChannelMap{}, method.default_parameters());
}

}  // namespace

TEST_CASE("ISG on the gallery: finite, and nearer the references than its one-ray inputs", "[isg]") {
    const AovSet one = render_gallery("gallery", 1);
    const AovSet reference = render_gallery("gallery", 64);

    const AovSet shadow = run("isg-shadow", one);
    REQUIRE(all_finite(shadow, Role::FilteredVisibility));
    REQUIRE(all_finite(shadow, Role::Beauty));
    CHECK(rms(shadow, Role::FilteredVisibility, reference, Role::Visibility) <
          0.8 * rms(one, roles::HardVisibility, reference, Role::Visibility));

    const AovSet glossy = run("isg-glossy", one);
    REQUIRE(all_finite(glossy, roles::GlossyReflection));
    const std::string glossy_pixels = role_info(roles::ThetaMax).channels[0];
    CHECK(rms(glossy, roles::GlossyReflection, reference, roles::GlossyReference, glossy_pixels) <
          0.8 * rms(one, roles::Reflection, reference, roles::GlossyReference, glossy_pixels));

    // Depth of field: the gallery through a thin lens focused on the post.
    const std::string lens = (aaf_test::scratch_dir("isg_gallery") / "gallery_lens.json").string();
    {
        std::ifstream in(std::string(AAF_SCENE_DIR) + "/gallery.json");
        std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        const std::string pinhole = "\"camera\": {";
        text.replace(
            text.find(pinhole), pinhole.size(),
            pinhole + "\"type\": \"thin_lens\", \"aperture_radius_m\": 0.15, \"focus_distance_m\": 4.6, ");
        std::ofstream(lens) << text;
    }
    const AovSet defocused_reference = render_gallery(lens, 64);
    const AovSet dof = run("isg-dof", defocused_reference);  // its pinhole.* is the in-focus input
    REQUIRE(all_finite(dof, roles::Defocused));
    CHECK(rms(dof, roles::Defocused, defocused_reference, Role::Beauty) <
          0.8 * rms(defocused_reference, roles::PinholeBeauty, defocused_reference, Role::Beauty));
}

TEST_CASE("The isg group's maps and glossy reference do not depend on the thread count", "[isg]") {
    trace::RenderSettings settings;
    settings.width = 24;
    settings.height = 18;
    settings.spp = 4;
    settings.aovs = {"isg"};
    settings.threads = 1;
    const AovSet one = trace::render_scene("gallery", settings);
    settings.threads = 3;
    const AovSet three = trace::render_scene("gallery", settings);
    REQUIRE(one.channel_names() == three.channel_names());
    for (std::size_t c = 0; c < one.channel_names().size(); ++c) {
        INFO(one.channel_names()[c]);
        CHECK(one.plane(c) == three.plane(c));
    }
}
