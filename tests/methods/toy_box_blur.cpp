// A toy method added from outside the library, as a plug-in would be: this
// one file and its registration line below. It declares a new input role,
// `toy_hit`, which the toy tracer group (toy_hit_group.cpp) writes, and an
// output role of its own. It then appears in `aaf filter --help` and
// `aaf info` of the `aaf_with_toy` build (the recipe for its input names the
// toy group), its roles in `--map` and the contract, and it runs through the
// property tests of every registered method (test_method_properties.cpp).
#include <algorithm>
#include <cmath>

#include "aaf/core/framework/method_registry.h"

namespace {

constexpr aaf::Role kToyHit{"toy_hit"};          // input, written by the toy_hits group
constexpr aaf::Role kToyBlurred{"toy_blurred"};  // output

/// A square box blur of toy_hit (no guides), clamped at the borders.
class ToyBoxBlur final : public aaf::Method {
  public:
    ToyBoxBlur() {
        info_.name = "toy_box";
        info_.title = "toy box blur";
        info_.summary = "Test plug-in: a square box blur of toy_hit";
        info_.reference = "none";
        info_.roles.declared = {
            {kToyHit, {"toy.hit"}, "[0, 1] times --toy-hit-value", "test plug-in: where the primary ray hit"},
            {kToyBlurred,
             {"toy.blurred"},
             "as toy_hit",
             "output of `aaf filter toy_box`: toy_hit, box-blurred"}};
        info_.roles.required = {kToyHit};
        info_.roles.outputs = {kToyBlurred};
        info_.roles.filtered = {{kToyHit, kToyBlurred}};
        info_.parameters = {
            aaf::ParameterInfo::integer("radius", "1", "pixels", "Half the box's side", 0, 16)};
    }

    const aaf::MethodInfo &info() const override { return info_; }

    void run(const aaf::MethodImages &images, const aaf::ParameterSet &parameters,
             aaf::Progress &) const override {
        const int r = parameters.get_int("radius"), width = images.width(), height = images.height();
        const aaf::ConstPlaneView in = images.input(kToyHit);
        const aaf::PlaneView out = images.output(kToyBlurred);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                double sum = 0;
                int count = 0;
                for (int ty = std::max(0, y - r); ty <= std::min(height - 1, y + r); ++ty)
                    for (int tx = std::max(0, x - r); tx <= std::min(width - 1, x + r); ++tx) {
                        const float v = in(tx, ty);
                        sum += std::isfinite(v) ? v : 0.0f;  // a NaN stays out of its neighbours
                        ++count;
                    }
                out(x, y) = float(sum / count);
            }
    }

  private:
    aaf::MethodInfo info_;
};

const aaf::MethodRegistration kToyBoxRegistration(std::make_unique<ToyBoxBlur>());

}  // namespace
