// A toy method added from outside the library, as a plug-in would be: this
// one file and its registration line below. It then appears in `aaf filter
// --help` and `aaf info` of the `aaf_with_toy` build and runs through the
// property tests of every registered method (test_method_properties.cpp).
#include <algorithm>
#include <cmath>

#include "aaf/core/method_registry.h"

namespace {

/// A square box blur of the visibility (no guides), clamped at the borders.
class ToyBoxBlur final : public aaf::Method {
  public:
    ToyBoxBlur() {
        info_.name = "toy_box";
        info_.title = "toy box blur";
        info_.summary = "Test plug-in: a square box blur of the visibility";
        info_.reference = "none";
        info_.roles.required = {aaf::Role::Visibility};
        info_.roles.outputs = {aaf::Role::FilteredVisibility};
        info_.roles.filtered = {{aaf::Role::Visibility, aaf::Role::FilteredVisibility}};
        info_.parameters = {
            aaf::ParameterInfo::integer("radius", "1", "pixels", "Half the box's side", 0, 16)};
    }

    const aaf::MethodInfo &info() const override { return info_; }

    void run(const aaf::MethodImages &images, const aaf::ParameterSet &parameters,
             aaf::Progress &) const override {
        const int r = parameters.get_int("radius"), width = images.width(), height = images.height();
        const aaf::ConstPlaneView in = images.input(aaf::Role::Visibility);
        const aaf::PlaneView out = images.output(aaf::Role::FilteredVisibility);
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
