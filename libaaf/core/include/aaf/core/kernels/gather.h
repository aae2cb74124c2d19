#pragma once

#include <cstddef>
#include <vector>

#include "aaf/core/contract/plane_view.h"
#include "aaf/core/util/frame_allocator.h"

namespace aaf {

/// Per-pixel guides of the world-space Gaussian gather that the methods share
/// (AAF Eq. 10-12, and the filters of the methods built on it): where each
/// pixel lies in the 2D plane distances are measured in, its normal and
/// object, and its own Gaussian's width and reach. Planar, row-major,
/// width x height. `resize` fills every plane with "not filtered";
/// `allocate` sizes them uninitialised, for a caller that writes every pixel.
struct GatherGuides {
    int width = 0, height = 0;
    /// Coordinates in the plane tap distances are measured in, world metres
    /// (AAF: the light's plane, so du^2 + dv^2 is the distance of AAF Eq. 12).
    FramePlane<float> coord_u_m, coord_v_m;
    /// Unit normal; zero where unknown (then only the centre itself counts).
    FramePlane<float> normal_x, normal_y, normal_z;
    /// Taps on another object are rejected; NaN matches nothing, not even itself,
    /// so a pixel with unusable geometry (non-finite position) is never a tap.
    FramePlane<float> object_id;
    /// 1 / (2 sigma^2) of the pixel's Gaussian, metres^-2.
    FramePlane<float> inv_two_sigma_sq;
    /// Optional (empty, or guide-sized): the Gaussian's 1 / (2 sigma^2) along
    /// v, so a tap weighs exp(-du^2 inv_two_sigma_sq - dv^2 this); empty =
    /// isotropic (AAF: one band-limit per light axis, aaf_bandlimits_axes()).
    FramePlane<float> inv_two_sigma_sq_v;
    bool anisotropic() const { return !inv_two_sigma_sq_v.empty(); }
    /// Taps reach this many pixels along each filtered axis; 0 = the pixel keeps its value.
    FramePlane<int> radius_px;
    /// Optional (all empty, or all guide-sized): a third coordinate n (metres)
    /// and, per centre pixel, shears a_u, a_v: a tap's offsets become
    /// du - a_u dn, dv - a_v dn, i.e. the tap is slid along a direction of the
    /// centre's choosing onto the centre's plane n = const (AAF: along the
    /// direction to the light, instead of AAF Eq. 12's orthogonal projection).
    /// With them, per centre, the weight 1 / (2 sigma_n^2) (metres^-2) of the
    /// offset dn itself: a tap weighs exp(... - dn^2 inv_two_sigma_sq_n) (AAF:
    /// the spread of the slide's direction over the light, 0 = none).
    FramePlane<float> coord_n_m, shear_u, shear_v, inv_two_sigma_sq_n;
    bool sheared() const { return !shear_u.empty(); }

    void resize(int width, int height);
    /// The seven planes and radius_px at width x height, their pixels
    /// uninitialised; the optional planes untouched.
    void allocate(int width, int height);
    std::size_t index(int x, int y) const { return std::size_t(y) * std::size_t(width) + std::size_t(x); }
};

/// How the 2D Gaussian is evaluated.
enum class GatherMode {
    Separable,  ///< a vertical then a horizontal 1D pass (AAF Sec. 6); exact where the width is locally
                ///< constant
    Full2D,     ///< every tap of the square window (AAF Eq. 10 directly)
};

class GatherBackend;

struct GatherSettings {
    /// Taps whose unit normal makes an angle above this with the centre's are
    /// rejected (AAF Sec. 6 "check on normal variation"); degrees, [0, 180].
    float normal_threshold_deg = 25.0f;
    GatherMode mode = GatherMode::Separable;
    /// Near an image edge, shorten the window on the far side too, so it stays
    /// centred on the pixel (unbiased on a linear gradient); false keeps the
    /// window cut on the edge side only.
    bool symmetric_borders = false;
    /// Where the sweeps run; null = the CPU (cpu_gather_backend()).
    const GatherBackend *backend = nullptr;

    /// Throws aaf::Error naming a setting out of range.
    void validate() const;
};

/// Gathers K channels with the same weights in one pass: every output pixel
/// with radius_px > 0 is the normalised sum over its accepted taps of
/// exp(-(du^2 + dv^2) inv_two_sigma_sq) (AAF Eq. 11-12; the normalisation of
/// the Gaussian cancels) times the source; the other pixels copy their source.
/// A tap counts when it lies on the centre's object with a normal within the
/// threshold; the centre always counts (with weight 1 if its own test fails).
/// Sums run in a fixed order, so the result does not depend on the thread
/// count; runs on the current oneTBB arena. Vectorised with runtime
/// dispatch: every instruction set with fused multiply-add (x86 AVX2 and
/// AVX-512, Arm) gives the same bits, as does every one without (SSE4 and
/// older); the two kinds differ by rounding (within 1e-6 on data in [0, 1]).
/// `sources[k]` and `outputs[k]` are guide-sized; an output may alias a
/// source (sources are read first).
/// Throws aaf::Error on mismatched sizes or counts.
void gather(const GatherGuides &guides, const GatherSettings &settings,
            const std::vector<ConstPlaneView> &sources, const std::vector<PlaneView> &outputs);

/// A per-axis factor of the tap weight: 1, cos(omega delta) or -sin(omega
/// delta), with delta the tap's displacement from the centre along that axis
/// of the guides' plane (metres) and omega the centre pixel's frequency
/// (radians per metre). MAAF's x-side kernels are products of such factors
/// with a Gaussian (MAAF Eq. 12-13: an offset pair of Gaussians in frequency
/// is a cos/sin-modulated Gaussian in space).
struct AxisModulation {
    enum class Kind { None, Cos, NegSin } kind = Kind::None;
    ConstPlaneView omega_rad_per_m;  ///< per centre pixel; unused for None
    /// Optional, per centre pixel, metres^-2: when given, the Gaussian along
    /// this axis is exp(-delta^2 * this) instead of the guides' isotropic
    /// width, so that a tap's weight can be anisotropic in the guides' plane
    /// (MAAF's 4D components pair two x-side widths, one per light axis).
    ConstPlaneView inv_two_sigma_sq;
};

/// Whether a modulated gather divides by the sum of its (unmodulated) Gaussian weights.
enum class GatherNormalisation {
    WeightSum,  ///< sum of w m s / sum of w: a constant source under m = 1 stays constant
    None,       ///< the raw sum of w m s: the caller normalises (MAAF filters f = 1 the same way)
};

/// The 2D gather over the full square window (GatherMode is ignored: a
/// product of cosines does not factor into two 1D passes) with each tap's
/// Gaussian weight w multiplied by m = m_u(du) m_v(dv). With both factors
/// None and WeightSum it equals gather() in Full2D mode.
void gather_modulated(const GatherGuides &guides, const GatherSettings &settings,
                      const std::vector<ConstPlaneView> &sources, const std::vector<PlaneView> &outputs,
                      const AxisModulation &along_u, const AxisModulation &along_v,
                      GatherNormalisation normalisation);

/// One sweep of a gather over the whole image (gather() runs one or two,
/// gather_modulated() one): every centre pixel with radius_px > 0 sums its
/// accepted taps along the enabled axes, as gather() documents; the others
/// copy their source. Planes are contiguous, row-major, the guides' size.
struct GatherSweepRequest {
    const GatherGuides *guides = nullptr;
    float cos_threshold = 1;  ///< cosine of GatherSettings::normal_threshold_deg
    bool symmetric_borders = false;
    bool along_x = true, along_y = true;
    /// gather_modulated()'s per-axis factors of the tap weight; both null in
    /// gather()'s sweeps, both set in gather_modulated()'s.
    const AxisModulation *modulation_u = nullptr, *modulation_v = nullptr;
    bool normalise = true;  ///< divide by the weight sum (false: GatherNormalisation::None)
    std::size_t channels = 0;
    const float *const *sources = nullptr;  ///< `channels` planes, read
    float *const *outputs = nullptr;        ///< `channels` planes, written (none aliases a source)
};

/// What runs a gather's sweeps: the seam between the methods' gathers and
/// the hardware. gather() and gather_modulated() check their arguments,
/// split a separable gather into its two sweeps and stage the planes, then
/// hand each sweep to GatherSettings::backend. A backend gives every pixel
/// the same bits whatever the thread count.
class GatherBackend {
  public:
    virtual ~GatherBackend() = default;
    virtual void sweep(const GatherSweepRequest &request) const = 0;
};

/// The CPU's backend: Highway SIMD rows for gather()'s sweeps (gather()'s
/// bits on each kind of instruction set), scalar loops for the modulated
/// ones, rows in parallel on the current oneTBB arena.
const GatherBackend &cpu_gather_backend();

}  // namespace aaf
