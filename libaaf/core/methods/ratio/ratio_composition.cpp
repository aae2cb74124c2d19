// The three estimators of the shadowed direct light from the same layers
// (ratio estimator Eq. 10, 11, 15) as planes to denoise and their composition.
#include "aaf/core/methods/ratio/ratio_composition.h"

#include <cmath>

#include "aaf/core/util/error.h"
#include "aaf/core/util/parallel.h"

namespace aaf {

namespace {

float finite_or_zero(float v) {
    return std::isfinite(v) ? v : 0.0f;
}

FramePlane<float> plane_of(ConstPlaneView view) {
    FramePlane<float> plane;
    plane.resize(std::size_t(view.width) * std::size_t(view.height));  // written in full below
    parallel_for_rows(view.height, [&](int y) {
        for (int x = 0; x < view.width; ++x)
            plane[std::size_t(y) * std::size_t(view.width) + std::size_t(x)] = finite_or_zero(view(x, y));
    });
    return plane;
}

}  // namespace

RatioComposition::RatioComposition(const RatioLayers &layers, RatioEstimator estimator, bool grey)
    : layers_(layers), estimator_(estimator), grey_(grey) {
    if (grey && estimator != RatioEstimator::Ratio)
        throw Error("the grey approximation applies to the ratio estimator only");
    const int width = layers.analytic[0].width, height = layers.analytic[0].height;
    auto check = [&](ConstPlaneView view, const char *what) {
        if (!view.valid() || view.width != width || view.height != height)
            throw Error(std::string("ratio estimator: layer ") + what + " is missing or has another size");
    };
    for (int c = 0; c < 3; ++c) {
        check(layers.analytic[c], "U");
        if (grey) continue;
        check(layers.shadowed[c], "S_N");
        if (estimator != RatioEstimator::Stochastic) check(layers.unshadowed[c], "U_N");
    }
    if (grey) {
        check(layers.shadowed_y, "S_N luminance");
        check(layers.unshadowed_y, "U_N luminance");
    }
}

int RatioComposition::plane_count() const {
    if (estimator_ == RatioEstimator::Ratio) return grey_ ? 2 : 6;
    return 3;
}

std::vector<FramePlane<float>> RatioComposition::sources() const {
    std::vector<FramePlane<float>> planes;
    switch (estimator_) {
        case RatioEstimator::Ratio:
            if (grey_) {
                planes.push_back(plane_of(layers_.shadowed_y));
                planes.push_back(plane_of(layers_.unshadowed_y));
            } else {
                for (int c = 0; c < 3; ++c) planes.push_back(plane_of(layers_.shadowed[c]));
                for (int c = 0; c < 3; ++c) planes.push_back(plane_of(layers_.unshadowed[c]));
            }
            break;
        case RatioEstimator::Stochastic:
            for (int c = 0; c < 3; ++c)
                planes.push_back(plane_of(layers_.shadowed[c]));  // ratio estimator Eq. 10
            break;
        case RatioEstimator::ControlVariate:
            for (int c = 0; c < 3; ++c) {
                const ConstPlaneView u = layers_.analytic[c], u_n = layers_.unshadowed[c],
                                     s_n = layers_.shadowed[c];
                FramePlane<float> plane;
                plane.resize(std::size_t(u.width) * std::size_t(u.height));  // written in full below
                parallel_for_rows(u.height, [&](int y) {
                    for (int x = 0; x < u.width; ++x)  // ratio estimator Eq. 11 with c = 1: U - (U_N - S_N)
                        plane[std::size_t(y) * std::size_t(u.width) + std::size_t(x)] =
                            finite_or_zero(u(x, y)) - finite_or_zero(u_n(x, y)) + finite_or_zero(s_n(x, y));
                });
                planes.push_back(std::move(plane));
            }
            break;
    }
    return planes;
}

}  // namespace aaf
