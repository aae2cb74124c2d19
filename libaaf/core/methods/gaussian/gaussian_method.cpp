// The fixed-width screen-space Gaussian: the "non-adaptive filter" baseline
// of AAF Fig. 6 and 10, as a registered method, so every method is compared
// against it through the same pipeline.
#include <array>
#include <cmath>
#include <vector>

#include "../builtin_methods.h"
#include "aaf/core/framework/parameter_defaults.h"
#include "aaf/core/kernels/fixed_gaussian.h"
#include "aaf/core/kernels/shadow_composition.h"
#include "aaf/core/util/frame_allocator.h"
#include "aaf/core/util/parallel.h"

namespace aaf {

namespace {

struct GaussianSettings {
    float sigma_px = 2;  ///< standard deviation of the Gaussian, cut at 3 sigma; 0 copies
};

const ParameterDeclarations<GaussianSettings> &gaussian_parameters() {
    static const auto declarations =
        std::move(ParameterDeclarations<GaussianSettings>("gaussian")
                      .real("sigma", &GaussianSettings::sigma_px, "pixels",
                            "Standard deviation of the Gaussian, cut at 3 sigma; 0 copies", 0, 256));
    return declarations;
}

/// Copies `in` into the packed plane `out`, a non-finite value as 0 so that it cannot spread through the
/// blur.
void finite_copy(ConstPlaneView in, float *out) {
    parallel_for_rows(in.height, [&](int y) {
        float *const row = out + std::size_t(y) * std::size_t(in.width);
        for (int x = 0; x < in.width; ++x) {
            const float v = in(x, y);
            row[x] = std::isfinite(v) ? v : 0.0f;
        }
    });
}

class GaussianMethod final : public Method {
  public:
    GaussianMethod() {
        info_.name = "gaussian";
        info_.title = "Gaussian";
        info_.summary =
            "Fixed-width screen-space Gaussian of the visibility (the non-adaptive baseline of AAF Fig. 6)";
        info_.reference = "baseline; Mehta, Wang, Ramamoorthi 2012, Fig. 6 and 10";
        info_.roles.required = {Role::Visibility, Role::Unshadowed};
        for (Role role : shadow_composition_roles())
            if (role != Role::Visibility) info_.roles.optional.push_back(role);
        info_.roles.outputs = {Role::FilteredVisibility, Role::Beauty};
        info_.roles.filtered = {{Role::Visibility, Role::FilteredVisibility}};
        info_.parameters = gaussian_parameters().infos();
    }

    const MethodInfo &info() const override { return info_; }

    void run(const MethodImages &images, const ParameterSet &parameters, Progress &progress) const override {
        const GaussianSettings settings = gaussian_parameters().read(parameters);
        const int width = images.width(), height = images.height();
        // Non-finite visibility is read as 0, so it cannot spread through the blur.
        FramePlane<float> visibility(std::size_t(width) * std::size_t(height));
        finite_copy(images.input(Role::Visibility), visibility.data());
        const PlaneView filtered = images.output(Role::FilteredVisibility);
        fixed_gaussian_filter(plane_view(visibility.data(), width, height), settings.sigma_px, filtered);
        progress.report(0.9);
        // Another renderer's pass of the key light gets the same screen-space blur.
        const PassFilter filter_pass = [&](const std::array<ConstPlaneView, 3> &pass,
                                           const std::array<PlaneView, 3> &out) {
            FramePlane<float> finite(visibility.size());
            for (std::size_t c = 0; c < 3; ++c) {
                finite_copy(pass[c], finite.data());
                fixed_gaussian_filter(plane_view(finite.data(), width, height), settings.sigma_px, out[c]);
            }
        };
        compose_shadowed_beauty(images, filtered, filter_pass);  // AAF Eq. 1, or the beauty corrected
    }

    std::string composition_note(const std::map<std::string, AttributeValue> &attributes,
                                 const std::function<bool(Role)> &has,
                                 Composition composition) const override {
        return shadow_beauty_note(shadow_beauty(attributes, has, composition, true), info_.title, true);
    }

  private:
    MethodInfo info_;
};

}  // namespace

std::unique_ptr<Method> make_gaussian_method() {
    return std::make_unique<GaussianMethod>();
}

std::vector<std::string> gaussian_parameter_defaults_read_back_differently() {
    return gaussian_parameters().defaults_read_back_differently();
}

}  // namespace aaf
