#pragma once

#include <string>
#include <vector>

namespace aaf::isg {

// Image Space Gathering (Robison and Shirley 2009): the formulas the three
// ISG filters share, and their point-sampled kernels' sample sets (ISG Eq. 4).

/// One tap of a kernel: an offset in units of the kernel's radius, inside the
/// unit disc (or the unit square scaled to a rectangle's aspect).
struct Tap {
    float x = 0, y = 0;
};

/// The shape of a sample set; for soft shadows the light's shape (ISG Sec. 3.1:
/// "a disk of samples will simulate a spherical light while a rectangular
/// array of samples will simulate a rectangular area light").
enum class TapShape { Disk, Rectangle };
/// grid: the regular k x k grid ISG Sec. 4 used; stratified: one fixed
/// jittered point per grid cell (a deterministic hash, the same for every pixel).
enum class TapPattern { Grid, Stratified };

/// `count` (a perfect square of an odd number: 1, 9, 25, 49, 81, ...) taps of a
/// k x k pattern over [-1, 1]^2, mapped to the unit disc by the Shirley-Chiu
/// concentric map (Disk) or scaled to half-extents (half_width, half_height),
/// the larger being 1 (Rectangle). The first tap is the centre (0, 0), so the
/// pixel being filtered is always among its own samples (ISG Eq. 4's i = 0).
/// Throws aaf::Error for any other count.
std::vector<Tap> tap_set(int count, TapShape shape, TapPattern pattern, float half_width = 1,
                         float half_height = 1);

/// ISG Eq. 8: the penumbra's world radius R_s = L d / (D - d) for a light of
/// size L (metres), an occluder at distance d from the receiver and the light
/// at distance D (metres). An occluder at or beyond the light gives +inf.
float penumbra_radius_m(float light_size_m, float occluder_distance_m, float light_distance_m);

/// ISG Eq. 5 and 9: a world length at eye depth `z_eye_m` projected to pixels
/// (length / z_eye times the focal length in pixels).
float screen_radius_px(float length_m, float z_eye_m, float focal_px);

/// ISG Eq. 13: the angle alpha (radians) of the cone, seen from the eye's
/// reflection, that has the glossy cone's cross-section at the reflected
/// object: tan(alpha) = E tan(theta_max) / (e + E), for eye distance e and
/// reflected distance E (metres; E = +inf gives theta_max).
float glossy_gather_angle(float theta_max_rad, float eye_distance_m, float reflected_distance_m);

/// ISG Eq. 15: the circle of confusion's radius in pixels, |z - z_f| / z
/// c_inf, for depth z (metres; +inf for the background) and focus depth z_f.
float circle_of_confusion_px(float depth_m, float focus_depth_m, float coc_at_infinity_px);

/// Hermite smoothstep of x between edges 0 and `width`: 0 below, 1 above.
float smoothstep(float width, float x);

}  // namespace aaf::isg
