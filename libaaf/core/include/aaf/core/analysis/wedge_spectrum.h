#pragma once

#include <cstdint>
#include <vector>

namespace aaf {

/// The double-wedge spectrum T of flatland soft shadows (MAAF Sec. 3, Fig. 4c).
/// Axes: Omega_x is the receiver's (image-side) frequency, Omega_y the light's,
/// both in radians per metre when x and y are in metres. A planar occluder of
/// slope s = d1/d2 - 1 puts its energy on the line Omega_x = Omega_y / s (the
/// orientation of MAAF Eq. 7: C_x^p > 0 where C_y^p > 0); occluders with slopes
/// in [s_min, s_max] fill the double wedge between the lines of s_max and s_min,
/// cut at |Omega_y| <= Omega_y^max by the light's spectrum. Coverage and
/// accuracy do not depend on Omega_y^max (every filter scales with it), so the
/// analysis uses 1.
struct DoubleWedge {
    double s_min = 1;        ///< smallest slope (widest part of the wedge), > 0
    double s_max = 2;        ///< largest slope, > s_min
    double omega_y_max = 1;  ///< light bandlimit Omega_y^max = 2/sigma_y (MAAF Sec. 3), > 0
};

/// Throws aaf::Error unless 0 < s_min < s_max and 0 < omega_y_max, all finite.
void check_double_wedge(const DoubleWedge &wedge);

/// Whether (omega_x, omega_y) lies in T: |Omega_y| <= Omega_y^max and Omega_x
/// between Omega_y/s_max and Omega_y/s_min (edges included).
bool in_double_wedge(const DoubleWedge &wedge, double omega_x, double omega_y);

/// Area of T, (Omega_y^max)^2 (1/s_min - 1/s_max) (MAAF Sec. 5).
double double_wedge_area(const DoubleWedge &wedge);

/// `count` wedges with 0 < s_min < s_max < s_upper, the range of MAAF Sec. 5
/// (s_upper = 10): each is two independent uniform draws on (0, s_upper),
/// sorted (pairs with a zero or equal draw are drawn again). Deterministic for
/// a seed on every platform: std::mt19937_64 with 53-bit doubles, no
/// implementation-defined distribution.
std::vector<DoubleWedge> uniform_sorted_wedges(int count, std::uint64_t seed, double s_upper = 10.0,
                                               double omega_y_max = 1.0);

}  // namespace aaf
