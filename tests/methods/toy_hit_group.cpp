// A toy AOV group added from outside the tracer, as a plug-in would be: this
// one file and its registration line below. It writes the role `toy_hit`
// that the toy method (toy_box_blur.cpp) declares and reads. It then appears
// in `--aovs` (parse_aov_groups, `aaf render --help` of the `aaf_with_toy`
// build), its parameter becomes an option of `aaf render`, `aaf info` names
// it as the recipe for toy_hit, and the property tests of every registered
// method render it (test_method_properties.cpp).
#include "aov_group.h"

namespace {

constexpr aaf::Role kToyHit{"toy_hit"};

/// toy_hit: `hit_value` where the pixel's primary ray hit a surface, 0 elsewhere.
class ToyHitGroup final : public aaf::trace::AovAccumulator {
  public:
    aaf::trace::AovGroupInfo info() const override {
        aaf::trace::AovGroupInfo info =
            aaf::trace::group_info("toy_hits", "toy_hit (test plug-in: where the primary ray hit)", roles());
        info.parameters = {
            aaf::ParameterInfo::real("toy_hit_value", "1", "", "the value written at a hit", 0)};
        return info;
    }
    std::vector<aaf::Role> roles() const override { return {kToyHit}; }
    void set_parameters(const aaf::ParameterSet &values) override {
        hit_value_ = values.get_float("toy_hit_value");
    }

    void write(const aaf::trace::RenderState &state, aaf::AovSet &aovs) const override {
        const aaf::PlaneView hit = aovs.add_channel(aaf::role_info(kToyHit).channels.front());
        state.for_each_pixel(
            [&](int x, int y, const aaf::trace::PrimaryHit &primary, const aaf::trace::ShadowStats &) {
                hit(x, y) = primary.found ? hit_value_ : 0.0f;
            });
    }

  private:
    float hit_value_ = 1;
};

const aaf::trace::AovGroupRegistration kToyHitRegistration([] {
    return std::unique_ptr<aaf::trace::AovAccumulator>(new ToyHitGroup);
});

}  // namespace
