// maaf6_row_sums for every instruction set Google Highway targets, chosen at
// run time: a vector of centres at a time, each lane its own centre with its
// own filter and its own sums in tap order. Compiled without contraction
// (CMakeLists.txt) and written with plain multiplies and adds, so every lane
// computes the same operations as every other instruction set's lanes: the
// same bits.
#include "aaf/core/methods/maaf6/maaf6_rows.h"

#include <algorithm>
#include <cstddef>

// Arrays of vectors need sized vector types: no scalable (SVE, RVV) targets.
#ifndef HWY_DISABLED_TARGETS
#define HWY_DISABLED_TARGETS (HWY_SVE | HWY_SVE2 | HWY_SVE_256 | HWY_SVE2_128 | HWY_RVV)
#endif
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "methods/maaf6/maaf6_rows.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "aaf/core/kernels/vector_math-inl.h"

HWY_BEFORE_NAMESPACE();
namespace aaf::detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using D = hn::ScalableTag<float>;
using V = hn::Vec<D>;
using M = hn::Mask<D>;

HWY_INLINE V dot3(V ax, V ay, V az, V bx, V by, V bz) {
    return hn::Add(hn::Add(hn::Mul(ax, bx), hn::Mul(ay, by)), hn::Mul(az, bz));
}

/// exp(-t^2 / 2) for t = x scale.
HWY_INLINE V gaussian(D d, V x, V scale) {
    const V t = hn::Mul(x, scale);
    return exp_nonpositive(d, hn::Mul(hn::Set(d, -0.5f), hn::Mul(t, t)));
}

/// A vector of centres' filters (Maaf6CentreField).
struct Centres {
    V p[3], n[3], t1[3], t2[3], scale[3], omega[2], gain[2], dc[2];
    V lens_scale, axis_scale, scale_px, radius, axis_radius;
    M pairs_lanes;         ///< the lanes that use the offset pairs
    int reach = -1;        ///< the largest radius of any lane; -1: no lane is filtered
    bool offsets = false;  ///< a lane uses the offset pairs
    bool lens = false;     ///< a lane filters the unoccluded light with the lens band
    bool axis = false;     ///< a lane has the axis-aligned filter beside the partition

    Centres(D d, const float *params, std::size_t stride) {
        const auto load = [&](int field) { return hn::LoadU(d, params + std::size_t(field) * stride); };
        for (int k = 0; k < 3; ++k) {
            p[k] = load(kCentrePx + k);
            n[k] = load(kCentreNx + k);
            t1[k] = load(kCentreT1x + k);
            t2[k] = load(kCentreT2x + k);
            scale[k] = load(kCentreScale0 + k);
        }
        for (int k = 0; k < 2; ++k) {
            omega[k] = load(kCentreOmega1 + k);
            gain[k] = load(kCentreGain1 + k);
            dc[k] = load(kCentreDc1 + k);
        }
        lens_scale = load(kCentreLensScale);
        axis_scale = load(kCentreAxisScale);
        scale_px = load(kCentreScalePixels);
        radius = load(kCentreRadius);
        axis_radius = load(kCentreAxisRadius);
        pairs_lanes = hn::Or(hn::Ne(gain[0], hn::Zero(d)), hn::Ne(gain[1], hn::Zero(d)));
        for (std::size_t lane = 0; lane < hn::Lanes(d); ++lane) {
            const auto at = [&](int field) { return params[std::size_t(field) * stride + lane]; };
            reach = std::max(reach, int(at(kCentreRadius)));
            offsets = offsets || at(kCentreGain1) != 0 || at(kCentreGain2) != 0;
            lens = lens || at(kCentreLensScale) > 0;
            axis = axis || at(kCentreAxisRadius) >= 0;
        }
    }
};

/// One axis's x kernel (maaf6_x_kernel) at displacement dx: functions 0 .. 2 pairs - 2 into k.
HWY_INLINE void x_kernel(D d, const Centres &c, V dx, int pairs, V *k) {
    k[0] = gaussian(d, dx, c.scale[0]);
    for (int p = 1; p < pairs; ++p) {
        const V envelope = gaussian(d, dx, c.scale[p]);
        V sin_phase, cos_phase;
        sin_cos(d, hn::Mul(c.omega[p - 1], dx), sin_phase, cos_phase);
        k[2 * p - 1] = hn::Mul(hn::Mul(c.gain[p - 1], hn::Sub(cos_phase, c.dc[p - 1])), envelope);
        k[2 * p] = hn::Mul(hn::Mul(hn::Neg(c.gain[p - 1]), sin_phase), envelope);
    }
}

/// Loads a plane's values for the lanes' taps (ty, first + lane): whole
/// vectors where the frame's memory holds them (a lane outside the image
/// then reads another row's value, which its mask discards), else lane by
/// lane, 0 outside the image.
class TapLoader {
  public:
    TapLoader(const Maaf6Taps &taps, int ty, std::ptrdiff_t first, std::size_t lanes)
        : index_(std::ptrdiff_t(ty) * taps.row_stride + first) {
        const std::ptrdiff_t end = std::ptrdiff_t(taps.height - 1) * taps.row_stride + taps.width;
        whole_ = index_ >= 0 && index_ + std::ptrdiff_t(lanes) <= end;
        if (whole_) return;
        for (std::size_t lane = 0; lane < lanes; ++lane) {
            const std::ptrdiff_t x = first + std::ptrdiff_t(lane);
            inside_[lane] = x >= 0 && x < taps.width;
        }
    }
    V operator()(D d, const float *plane) const {
        if (whole_) return hn::LoadU(d, plane + index_);
        HWY_ALIGN float values[kMaaf6RowPadding];
        for (std::size_t lane = 0; lane < hn::Lanes(d); ++lane)
            values[lane] = inside_[lane] ? plane[index_ + std::ptrdiff_t(lane)] : 0.0f;
        return hn::Load(d, values);
    }

  private:
    std::ptrdiff_t index_;
    bool whole_ = true;
    bool inside_[kMaaf6RowPadding] = {};
};

/// acc += value where `m` (a rejected lane's value, whatever it holds, adds nothing).
HWY_INLINE void add(M m, V &acc, V value) {
    acc = hn::Add(acc, hn::IfThenElseZero(m, value));
}

/// Adds kernel times a tap's weight and R, G, B sums to a filter's four
/// sums where `m`: the sums are the caller's registers, so that a vector's
/// 25 channels add to them in order without a trip through memory.
HWY_INLINE void add_channel(M m, V kernel, V weight, V r, V g, V b, V &den, V &num_r, V &num_g, V &num_b) {
    add(m, den, hn::Mul(kernel, weight));
    add(m, num_r, hn::Mul(kernel, r));
    add(m, num_g, hn::Mul(kernel, g));
    add(m, num_b, hn::Mul(kernel, b));
}

/// One accepted (in some lane) tap's contributions to a vector of centres'
/// sums (maaf6_filter.cpp's add_tap), `kPairs` pairs per axis: 3 where a
/// lane uses the offset pairs, else 1.
template <int kPairs>
HWY_INLINE void add_tap(D d, const Maaf6Taps &taps, const Centres &c, const TapLoader &load, M accepted,
                        V tap_px, V tap_py, V tap_pz, V offset_x, V offset_y, V *acc) {
    constexpr int kFunctions = 2 * kPairs - 1;
    const V dx = hn::Sub(tap_px, c.p[0]), dy = hn::Sub(tap_py, c.p[1]), dz = hn::Sub(tap_pz, c.p[2]);
    V k1[kFunctions], k2[kFunctions];
    const V inv_samples = load(d, taps.inv_samples);
    // A lane without offset pairs has the central Gaussian alone along t1, t2 and the normal: one
    // exponential of the whole displacement (the frame is orthonormal), times 1 / samples, in k1[0]
    // (k2[0] = 1), whatever its neighbours in the vector use (so every vector width gives its bits).
    const V scaled_sq = hn::Mul(dot3(dx, dy, dz, dx, dy, dz), hn::Mul(c.scale[0], c.scale[0]));
    const V central_only = hn::Mul(exp_nonpositive(d, hn::Mul(hn::Set(d, -0.5f), scaled_sq)), inv_samples);
    if constexpr (kPairs > 1) {
        const V d1 = dot3(dx, dy, dz, c.t1[0], c.t1[1], c.t1[2]);
        const V d2 = dot3(dx, dy, dz, c.t2[0], c.t2[1], c.t2[2]);
        const V dn = dot3(dx, dy, dz, c.n[0], c.n[1], c.n[2]);
        x_kernel(d, c, d1, kPairs, k1);
        x_kernel(d, c, d2, kPairs, k2);
        // Off the tangent plane, the central Gaussian of that distance; per-pixel means.
        const V per_sample = hn::Mul(gaussian(d, dn, c.scale[0]), inv_samples);
        for (int a = 0; a < kFunctions; ++a) k1[a] = hn::Mul(k1[a], per_sample);
        k1[0] = hn::IfThenElse(c.pairs_lanes, k1[0], central_only);
        k2[0] = hn::IfThenElse(c.pairs_lanes, k2[0], hn::Set(d, 1.0f));
    } else {
        k1[0] = central_only;
        k2[0] = hn::Set(d, 1.0f);
    }
    const V weight0 = load(d, taps.weights[0]);
    const V sum0_r = load(d, taps.sums[0]), sum0_g = load(d, taps.sums[1]), sum0_b = load(d, taps.sums[2]);
    V den = acc[kSumDen], num_r = acc[kSumNumR], num_g = acc[kSumNumG], num_b = acc[kSumNumB];
    for (int a = 0; a < kFunctions; ++a)
        for (int b = 0; b < kFunctions; ++b) {
            const int channel = a * kMaaf6Functions + b;
            const V kernel = hn::Mul(k1[a], k2[b]);
            if (channel == 0) {
                add_channel(accepted, kernel, weight0, sum0_r, sum0_g, sum0_b, den, num_r, num_g, num_b);
            } else {
                const float *const *sums = taps.sums + 3 * channel;
                add_channel(accepted, kernel, load(d, taps.weights[channel]), load(d, sums[0]),
                            load(d, sums[1]), load(d, sums[2]), den, num_r, num_g, num_b);
            }
        }
    acc[kSumDen] = den;
    acc[kSumNumR] = num_r;
    acc[kSumNumG] = num_g;
    acc[kSumNumB] = num_b;
    add_channel(accepted, hn::Mul(k1[0], k2[0]), weight0, sum0_r, sum0_g, sum0_b, acc[kSumDen0],
                acc[kSumNum0R], acc[kSumNum0G], acc[kSumNum0B]);
    if (c.lens) {  // the unoccluded light through the lens band: a Gaussian of the whole displacement
        const M lens = hn::And(accepted, hn::Gt(c.lens_scale, hn::Zero(d)));
        const V lens_sq = hn::Mul(dot3(dx, dy, dz, dx, dy, dz), hn::Mul(c.lens_scale, c.lens_scale));
        const V kernel = exp_nonpositive(d, hn::Mul(hn::Set(d, -0.5f), lens_sq));
        add(lens, acc[kSumUnoccluded], hn::Mul(hn::Mul(kernel, weight0), inv_samples));
        add(lens, acc[kSumUnoccludedDen], kernel);
    }
    if constexpr (kPairs == 1) return;
    // The central envelope's mass the guides keep, and the axis-aligned filter over its own window.
    add(accepted, acc[kSumMassKept],
        hn::Mul(gaussian(d, offset_x, c.scale_px), gaussian(d, offset_y, c.scale_px)));
    if (!c.axis) return;
    const M axis = hn::And(accepted, hn::And(hn::Le(hn::Abs(offset_x), c.axis_radius),
                                             hn::Le(hn::Abs(offset_y), c.axis_radius)));
    // As a lane without offset pairs computes it (one exponential of the whole displacement), so that
    // a cut window gets `--pairs 1`'s bits.
    const V axis_sq = hn::Mul(dot3(dx, dy, dz, dx, dy, dz), hn::Mul(c.axis_scale, c.axis_scale));
    const V kernel = hn::Mul(exp_nonpositive(d, hn::Mul(hn::Set(d, -0.5f), axis_sq)), inv_samples);
    add_channel(axis, kernel, weight0, sum0_r, sum0_g, sum0_b, acc[kSumDen1], acc[kSumNum1R], acc[kSumNum1G],
                acc[kSumNum1B]);
}

void RowSums(const Maaf6Taps &taps, int y, int count, const float *params, std::size_t stride, float *sums) {
    const D d;
    const std::size_t lanes = hn::Lanes(d);
    const V cos_threshold = hn::Set(d, taps.cos_threshold);
    for (std::size_t x0 = 0; x0 < std::size_t(count); x0 += lanes) {
        const Centres c(d, params + x0, stride);
        V acc[kSumFieldCount];
        for (V &a : acc) a = hn::Zero(d);
        const V centre_x = hn::Add(hn::Iota(d, 0.0f), hn::Set(d, float(x0)));
        for (int ty = std::max(0, y - c.reach); ty <= std::min(taps.height - 1, y + c.reach); ++ty) {
            const V offset_y = hn::Set(d, float(ty - y));
            const M row_inside = hn::Le(hn::Abs(offset_y), c.radius);
            if (hn::AllFalse(d, row_inside)) continue;
            for (int dx = -c.reach; dx <= c.reach; ++dx) {
                const std::ptrdiff_t first = std::ptrdiff_t(x0) + dx;
                const V offset_x = hn::Set(d, float(dx));
                const V tap_x = hn::Add(centre_x, offset_x);
                const M inside = hn::And(
                    hn::And(row_inside, hn::Le(hn::Abs(offset_x), c.radius)),
                    hn::And(hn::Ge(tap_x, hn::Zero(d)), hn::Lt(tap_x, hn::Set(d, float(taps.width)))));
                if (hn::AllFalse(d, inside)) continue;
                const TapLoader load(taps, ty, first, lanes);
                // tap_accepted(): a hit with samples (else its normal is NaN) within the normal threshold.
                const V cos_angle =
                    dot3(c.n[0], c.n[1], c.n[2], load(d, taps.nx), load(d, taps.ny), load(d, taps.nz));
                const M accepted = hn::And(inside, hn::Ge(cos_angle, cos_threshold));
                if (hn::AllFalse(d, accepted)) continue;
                const V tap_px = load(d, taps.px), tap_py = load(d, taps.py), tap_pz = load(d, taps.pz);
                if (c.offsets)
                    add_tap<3>(d, taps, c, load, accepted, tap_px, tap_py, tap_pz, offset_x, offset_y, acc);
                else
                    add_tap<1>(d, taps, c, load, accepted, tap_px, tap_py, tap_pz, offset_x, offset_y, acc);
            }
        }
        for (int f = 0; f < kSumFieldCount; ++f) hn::StoreU(acc[f], d, sums + std::size_t(f) * stride + x0);
    }
}

}  // namespace HWY_NAMESPACE
}  // namespace aaf::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "aaf/core/util/instruction_set.h"

namespace aaf::detail {

HWY_EXPORT(RowSums);

void maaf6_row_sums(const Maaf6Taps &taps, int y, int count, const float *params, std::size_t stride,
                    float *sums) {
    (void)instruction_set();  // applies AAF_ISA before the first dispatch
    HWY_DYNAMIC_DISPATCH(RowSums)(taps, y, count, params, stride, sums);
}

}  // namespace aaf::detail
#endif
