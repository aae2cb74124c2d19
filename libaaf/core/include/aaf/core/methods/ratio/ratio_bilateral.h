#pragma once

#include <array>
#include <vector>

#include "aaf/core/contract/plane_view.h"
#include "aaf/core/methods/ratio/ratio_composition.h"

namespace aaf {

/// The geometry the ratio estimator's joint bilateral weighs taps with.
struct RatioBilateralGuides {
    std::array<ConstPlaneView, 3> position;  ///< world metres
    std::array<ConstPlaneView, 3> normal;    ///< unit (renormalised here)
    /// The scene scale plane distances are measured in: the world length one
    /// pixel covers (the PixelSize role, or a scene-bounds fallback), metres.
    /// A pixel with a non-positive or non-finite scale or position is no
    /// surface: never a tap, and never filtered.
    ConstPlaneView scale_m;
};

struct RatioBilateralSettings {
    /// A tap at distance d from the centre's tangent plane (position, normal)
    /// weighs exp(-(d / (plane_sigma x scale_m))^2 / 2); in pixel footprints.
    float plane_sigma = 1.0f;
    /// Taps reach ceil(cutoff_sigmas x sigma) pixels (3: weights below exp(-4.5) dropped).
    float cutoff_sigmas = 3.0f;
};

/// The ratio estimator's joint bilateral (Sec. 4.1, passes 3-4): a horizontal
/// then a vertical pass, each tap weighted by exp(-t^2 / (2 sigma^2)) with
/// sigma = `sigma_px` at the centre pixel, times the plane-distance weight of
/// RatioBilateralSettings; every plane of `sources` is filtered with the same
/// weights in the same pass. A pixel with sigma_px = 0 costs nothing and keeps
/// its value. The vertical pass writes `composition`'s radiance (U x den(S_N) /
/// den(U_N) for the ratio estimator) straight to `rgb`, added to it when
/// `accumulate`. `sources` are composition.plane_count() guide-sized planes of finite values.
/// Deterministic for any thread count; throws aaf::Error on mismatched sizes.
void ratio_bilateral_compose(const RatioBilateralGuides &guides, ConstPlaneView sigma_px,
                             const RatioBilateralSettings &settings,
                             const std::vector<ConstPlaneView> &sources, const RatioComposition &composition,
                             const std::array<PlaneView, 3> &rgb, bool accumulate);

/// The same two passes writing the filtered planes themselves (`outputs`,
/// one per source, guide-sized; they may not alias the sources; at most 8 sources).
void ratio_bilateral(const RatioBilateralGuides &guides, ConstPlaneView sigma_px,
                     const RatioBilateralSettings &settings, const std::vector<ConstPlaneView> &sources,
                     const std::vector<PlaneView> &outputs);

}  // namespace aaf
