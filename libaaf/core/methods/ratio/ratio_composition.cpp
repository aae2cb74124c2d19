// The three estimators of the shadowed direct light from the same layers
// (ratio estimator Eq. 10, 11, 15) as planes to denoise and their composition.
#include "aaf/core/methods/ratio/ratio_composition.h"

#include <cmath>

#include "aaf/core/methods/ratio/ratio_rows.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/parallel.h"

namespace aaf {

namespace {

float finite_or_zero(float v) {
    return std::isfinite(v) ? v : 0.0f;
}

/// Packed copies of `views` (one size), non-finite values read as 0, in one
/// pass over the rows (one parallel region, not one per plane).
std::vector<FramePlane<float>> planes_of(const std::vector<ConstPlaneView> &views) {
    std::vector<FramePlane<float>> planes(views.size());
    const int width = views.front().width, height = views.front().height;
    for (FramePlane<float> &plane : planes)
        plane.resize(std::size_t(width) * std::size_t(height));  // written in full below
    parallel_for_rows(height, [&](int y) {
        for (std::size_t k = 0; k < views.size(); ++k) {
            float *row = &planes[k][std::size_t(y) * std::size_t(width)];
            for (int x = 0; x < width; ++x) row[x] = finite_or_zero(views[k](x, y));
        }
    });
    return planes;
}

}  // namespace

void RatioComposition::compose_row(int y, int x_begin, int x_end, const float *const *denoised,
                                   const std::array<PlaneView, 3> &rgb, bool accumulate) const {
    bool adjacent = estimator_ == RatioEstimator::Ratio;
    for (int c = 0; c < 3; ++c) adjacent &= rgb[c].pixel_stride == 1 && layers_.analytic[c].pixel_stride == 1;
    if (adjacent) {
        for (int c = 0; c < 3; ++c)
            detail::ratio_compose_row(&layers_.analytic[c](x_begin, y), denoised[grey_ ? 0 : c],
                                      denoised[grey_ ? 1 : 3 + c], x_end - x_begin, accumulate,
                                      &rgb[c](x_begin, y));
        return;
    }
    float values[8];
    for (int x = x_begin; x < x_end; ++x) {
        for (int k = 0; k < plane_count(); ++k) values[k] = denoised[k][x - x_begin];
        float pixel[3] = {rgb[0](x, y), rgb[1](x, y), rgb[2](x, y)};
        compose(x, y, values, pixel, accumulate);
        for (int c = 0; c < 3; ++c) rgb[c](x, y) = pixel[c];
    }
}

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
            if (grey_) return planes_of({layers_.shadowed_y, layers_.unshadowed_y});
            return planes_of({layers_.shadowed[0], layers_.shadowed[1], layers_.shadowed[2],
                              layers_.unshadowed[0], layers_.unshadowed[1], layers_.unshadowed[2]});
        case RatioEstimator::Stochastic:
            // ratio estimator Eq. 10
            return planes_of({layers_.shadowed[0], layers_.shadowed[1], layers_.shadowed[2]});
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
