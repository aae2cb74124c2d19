// isg-shadow's per-pixel loops (isg_rows.h: shadow_row,
// prepare_shadow_sweep) for every instruction set Google Highway targets,
// chosen at run time: the packed rows and tiles, the search (ISG Eq. 4-7)
// and the gather (ISG Eq. 4, 8-9), one pixel per lane.
#include "isg_rows.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

// Arrays of lanes need sized vector types: no scalable (SVE, RVV) targets.
#ifndef HWY_DISABLED_TARGETS
#define HWY_DISABLED_TARGETS (HWY_SVE | HWY_SVE2 | HWY_SVE_256 | HWY_SVE2_128 | HWY_RVV)
#endif
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "methods/isg/isg_shadow_rows.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "aaf/core/kernels/vector_math-inl.h"
#include "methods/isg/isg_lanes-inl.h"

HWY_BEFORE_NAMESPACE();
namespace aaf::isg {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

/// exp(-l^2 / sigma), l = |p - p0| / scene size (ISG Eq. 6-7), at least
/// 2^-64 (exp2_nonpositive()'s floor: a far tap still counts where no other
/// does, as the exponential's own tiny value did); NaN lanes are dropped
/// from `m` (a non-finite weight passes the tap over).
HWY_INLINE VF shadow_range(const ShadowSweep &s, const Point &p, const Point &p0, MF &m) {
    const DF df;
    // In base 2, from the squared distance with the constants folded: no square root per tap.
    const Point delta = p - p0;
    const float scale = -1.44269504f * (s.range.inv_scene_size * s.range.inv_scene_size) * s.range.inv_sigma;
    const VF exponent = hn::Mul(dot(delta, delta), hn::Set(df, scale));
    m = hn::AndNot(hn::IsNaN(exponent), m);
    return detail::HWY_NAMESPACE::exp2_nonpositive(df, exponent);
}

/// The lanes' pixels in the packed planes of ShadowScratch (dense, row
/// after row, layout `dense`): `base` their own indices.
struct ShadowBlock {
    RowLanes lanes;
    PlaneLayout dense;
    VI base;
};

/// The index in the packed planes of the lanes' taps at (tap_x, tap_y)
/// times `radius_px`; a tap outside the image is dropped from `m` (never
/// one of an interior block).
template <bool kInterior>
HWY_INLINE VI shadow_tap(const ShadowBlock &b, VF radius_px, float tap_x, float tap_y, MF &m) {
    const DI di;
    // radius_px is >= 0 and at most max_radius_px (clamp_radius()), |tap| <= 1.
    const VI dx = round_half_away(tap_x, radius_px), dy = round_half_away(tap_y, radius_px);
    if constexpr (kInterior) {
        return hn::Add(b.base, hn::Add(hn::Mul(dy, hn::Set(di, b.dense.width)), dx));
    } else {
        const TapPixel tap = tap_pixel(b.dense, b.lanes.x, b.lanes.y, dx, dy);
        m = hn::And(m, tap.inside);
        return tap.index;
    }
}

/// One tap of a vector of pixels, read: the lanes it counts for, its
/// packed point and value.
struct ShadowTap {
    MF m;
    Point p;
    VF value;
};

/// Tap `t` of `taps` scaled by `radius_px` for the lanes in `m`, read from
/// `packed` (the index is clamped, so the read is safe for every lane); for
/// the search (kSearch) only where the packed distance is >= 0: in shadow,
/// ISG Eq. 6's inShadow, with a valid distance.
template <bool kInterior, bool kSearch>
HWY_INLINE ShadowTap read_shadow_tap(const ShadowBlock &b, const float *packed, const TapArrays &taps, int t,
                                     VF radius_px, MF m) {
    const DF df;
    ShadowTap tap;
    const VI index = shadow_tap<kInterior>(b, radius_px, taps.x[t], taps.y[t], m);
    load_quadruples(df, packed, index, tap.p, tap.value);
    tap.m = kSearch ? hn::And(m, hn::Ge(tap.value, hn::Zero(df))) : m;
    return tap;
}

/// ISG Eq. 4's sums over `taps` for the lanes in `m`, with the range
/// weights of ISG Eq. 6-7. Taps go two at a time, so that one's weight (an
/// exponential, long in latency) overlaps the other's; they are added in
/// order. A pair with no lane to count is passed over; a tap with none in
/// a pair adds zeros, which leave the sums' bits as they are (add_finite()).
template <bool kInterior, bool kSearch>
HWY_INLINE WeightedSums<1> shadow_sums(const ShadowSweep &s, const ShadowBlock &b, const float *packed,
                                       const TapArrays &taps, VF radius_px, MF m, const Point &p0) {
    const DF df;
    WeightedSums<1> sums;
    const int count = taps.count();
    int t = 0;
    for (; t + 1 < count; t += 2) {
        ShadowTap first = read_shadow_tap<kInterior, kSearch>(b, packed, taps, t, radius_px, m);
        ShadowTap second = read_shadow_tap<kInterior, kSearch>(b, packed, taps, t + 1, radius_px, m);
        if (hn::AllFalse(df, hn::Or(first.m, second.m))) continue;
        const VF w_first = shadow_range(s, first.p, p0, first.m);
        const VF w_second = shadow_range(s, second.p, p0, second.m);
        sums.add_finite(first.m, w_first, {first.value});
        sums.add_finite(second.m, w_second, {second.value});
    }
    if (t < count) {
        ShadowTap last = read_shadow_tap<kInterior, kSearch>(b, packed, taps, t, radius_px, m);
        if (!hn::AllFalse(df, last.m)) {
            const VF w = shadow_range(s, last.p, p0, last.m);
            sums.add_finite(last.m, w, {last.value});
        }
    }
    return sums;
}

/// ISG Eq. 4-7: the mean occluder distance of the in-shadow taps within
/// `radius_px` (shadow_search_radius()); false lanes found none. The packed
/// occluder distance is negative where a tap is not in shadow (ISG Eq. 6's
/// inShadow) or has no valid distance.
template <bool kInterior>
HWY_INLINE MF shadow_search(const ShadowSweep &s, const ShadowBlock &b, MF valid, const Point &p0,
                            VF radius_px, VF &occluder_m) {
    const WeightedSums<1> sums = shadow_sums<kInterior, true>(s, b, s.scratch->position_occluder.data(),
                                                              *s.search, radius_px, valid, p0);
    occluder_m = sums.mean(0);
    return hn::And(valid, sums.positive());
}

/// The gather of ISG Eq. 4: the hard visibility within `radius_px`
/// (shadow_gather_radius()), for the lanes in `found`; else `hard0`. A tap
/// whose V is not finite has a NaN weight, which passes it over (PackShadowRow()).
template <bool kInterior>
HWY_INLINE VF shadow_gather(const ShadowSweep &s, const ShadowBlock &b, MF found, const Point &p0,
                            VF radius_px, VF hard0) {
    const WeightedSums<1> sums =
        shadow_sums<kInterior, false>(s, b, s.scratch->position_hard.data(), *s.gather, radius_px, found, p0);
    return hn::IfThenElse(hn::And(found, sums.positive()), sums.mean(0), hard0);
}

/// ISG Eq. 5: the search's radius, the light's size projected at the pixel's depth.
HWY_INLINE VF shadow_search_radius(const ShadowSweep &s, VF z_eye) {
    const DF df;
    return clamp_radius(hn::Mul(hn::Div(hn::Set(df, s.light_size_m), z_eye), hn::Set(df, s.focal_px)),
                        s.range.max_radius_px);
}

/// ISG Eq. 8-9: the gather's radius, the penumbra's width projected at the pixel's depth.
HWY_INLINE VF shadow_gather_radius(const ShadowSweep &s, const Point &p0, VF z_eye, VF occluder_m) {
    const DF df;
    const VF light_distance_m = length(broadcast(s.light_center) - p0);
    const VF gap_m = hn::Sub(light_distance_m, occluder_m);
    const VF penumbra_m = hn::IfThenElse(hn::Gt(gap_m, hn::Zero(df)),
                                         hn::Div(hn::Mul(hn::Set(df, s.light_size_m), occluder_m), gap_m),
                                         hn::Set(df, kInf));  // ISG Eq. 8
    return clamp_radius(hn::Mul(hn::Div(penumbra_m, z_eye), hn::Set(df, s.focal_px)),
                        s.range.max_radius_px);  // ISG Eq. 9
}

/// The pixels the taps of the lanes can reach, `taps` scaled by radii up to
/// the largest of `radius_px` (a tap's offset rounds |t| r to at most
/// ceil(max |t| max r); one pixel more for safety).
struct Window {
    int x_lo, x_hi, y_lo, y_hi;
};

HWY_INLINE Window tap_window(const RowLanes &lanes, const TapArrays &taps, VF radius_px) {
    const DF df;
    const float r = hn::GetLane(hn::MaxOfLanes(df, radius_px));
    const int reach_x = int(std::ceil(taps.max_abs_x * r)) + 1,
              reach_y = int(std::ceil(taps.max_abs_y * r)) + 1;
    const int x0 = hn::GetLane(lanes.x), y = hn::GetLane(lanes.y);
    return {x0 - reach_x, x0 + int(hn::Lanes(df)) - 1 + reach_x, y - reach_y, y + reach_y};
}

/// Whether every tap of the window is inside the image (and the lanes fill a vector).
HWY_INLINE bool interior(const ShadowBlock &b, const Window &window) {
    return b.lanes.count == int(hn::Lanes(DF())) && window.x_lo >= 0 && window.y_lo >= 0 &&
           window.x_hi < b.dense.width && window.y_hi < b.dense.height;
}

/// How many tiles of `window` (clipped to the image) `table` of ShadowTiles counts.
HWY_INLINE int tile_count(const ShadowSweep &s, const std::vector<int> &table, const Window &window) {
    constexpr int k = ShadowTiles::kTilePx;
    const int c0 = std::max(window.x_lo, 0) / k, c1 = std::min(window.x_hi, s.layout.width - 1) / k + 1;
    const int r0 = std::max(window.y_lo, 0) / k, r1 = std::min(window.y_hi, s.layout.height - 1) / k + 1;
    const std::size_t stride = std::size_t(s.scratch->tiles.columns) + 1;
    const auto at = [&](int r, int c) { return table[std::size_t(r) * stride + std::size_t(c)]; };
    return at(r1, c1) - at(r0, c1) - at(r1, c0) + at(r0, c0);
}

/// Whether every pixel of `window` is exactly 1 or every one exactly +0: a
/// gather within it returns that value (the weighted sum of ones is the sum
/// of the weights, of zeros zero), which is also the lanes' own.
HWY_INLINE bool uniform(const ShadowSweep &s, const Window &window) {
    const ShadowTiles &tiles = s.scratch->tiles;
    return s.pass_over_uniform &&
           (tile_count(s, tiles.not_lit, window) == 0 || tile_count(s, tiles.not_dark, window) == 0);
}

/// One vector of pixels: the search (ISG Eq. 4-7), then the gather (ISG Eq.
/// 4, 8-9) of the lanes that found an occluder; the others keep `hard0`.
/// Blocks whose taps stay where no search can find an occluder, or where
/// every gather returns the lanes' own value, skip that work (ShadowTiles).
/// Radii are zeroed outside the lanes that use them, which then reach no further.
HWY_INLINE VF shadow_pixels(const ShadowSweep &s, const ShadowBlock &b, MF valid, const Point &p0, VF z_eye,
                            VF hard0) {
    const DF df;
    if (hn::AllFalse(df, valid)) return hard0;
    const VF search_px = hn::IfThenElseZero(valid, shadow_search_radius(s, z_eye));
    const Window search_window = tap_window(b.lanes, *s.search, search_px);
    if (s.pass_over_uniform && tile_count(s, s.scratch->tiles.in_shadow, search_window) == 0) return hard0;
    if (uniform(s, tap_window(b.lanes, *s.gather, hn::Set(df, s.range.max_radius_px)))) return hard0;
    VF occluder_m;
    const MF found = interior(b, search_window)
                         ? shadow_search<true>(s, b, valid, p0, search_px, occluder_m)
                         : shadow_search<false>(s, b, valid, p0, search_px, occluder_m);
    if (hn::AllFalse(df, found)) return hard0;
    const VF gather_px = hn::IfThenElseZero(found, shadow_gather_radius(s, p0, z_eye, occluder_m));
    const Window gather_window = tap_window(b.lanes, *s.gather, gather_px);
    if (uniform(s, gather_window)) return hard0;
    return interior(b, gather_window) ? shadow_gather<true>(s, b, found, p0, gather_px, hard0)
                                      : shadow_gather<false>(s, b, found, p0, gather_px, hard0);
}

/// Packs row `y`: (P, V) and (P, d) per pixel. d = -1 where the search
/// passes the pixel over (not in shadow, or no distance >= 0 and finite);
/// where V is not finite, the gather's P.x is NaN (so is the tap's weight,
/// which passes it over) and V 0, so that every packed value is finite.
void PackShadowRow(const ShadowSweep &s, ShadowScratch &scratch, int y) {
    const DF df;
    const std::ptrdiff_t row = std::ptrdiff_t(y) * s.layout.width;
    float *position_hard = scratch.position_hard.data() + 4 * row;
    float *position_occluder = scratch.position_occluder.data() + 4 * row;
    for (int x0 = 0; x0 < s.layout.width; x0 += int(hn::Lanes(df))) {
        const RowLanes lanes = row_lanes(s.layout, x0, y);
        const VF hard = load_centre(s.hard, lanes), d = load_centre(s.occluder_m, lanes);
        const MF searched = hn::And(hn::Lt(hard, hn::Set(df, 0.5f)),  // inShadow of ISG Eq. 6
                                    hn::And(hn::Ge(d, hn::Zero(df)), hn::IsFinite(d)));
        const MF finite = hn::IsFinite(hard);
        const VF x_m = load_centre(s.position[0], lanes);
        HWY_ALIGN float x[kMaxLanes], x_gather[kMaxLanes], y_m[kMaxLanes], z[kMaxLanes], v[kMaxLanes],
            occluder[kMaxLanes];
        hn::Store(x_m, df, x);
        hn::Store(hn::IfThenElse(finite, x_m, hn::Set(df, NAN)), df, x_gather);
        hn::Store(load_centre(s.position[1], lanes), df, y_m);
        hn::Store(load_centre(s.position[2], lanes), df, z);
        hn::Store(hn::IfThenElseZero(finite, hard), df, v);
        hn::Store(hn::IfThenElse(searched, d, hn::Set(df, -1.0f)), df, occluder);
        for (int i = 0; i < lanes.count; ++i) {
            float *q = position_hard + 4 * std::ptrdiff_t(x0 + i);
            float *o = position_occluder + 4 * std::ptrdiff_t(x0 + i);
            q[0] = x_gather[i];
            o[0] = x[i];
            q[1] = o[1] = y_m[i];
            q[2] = o[2] = z[i];
            q[3] = v[i];
            o[3] = occluder[i];
        }
    }
}

void ShadowRow(const ShadowSweep &s, int y) {
    const DF df;
    const DI di;
    const PlaneLayout dense = {s.layout.width, s.layout.height, s.layout.width, 1};
    for (int x0 = 0; x0 < s.layout.width; x0 += int(hn::Lanes(df))) {
        const ShadowBlock b = {row_lanes(s.layout, x0, y), dense, hn::Iota(di, y * dense.width + x0)};
        const RowLanes &lanes = b.lanes;
        const VF hard0 = load_centre(s.hard, lanes), z_eye = load_centre(s.depth_m, lanes);
        const Point p0 = load_centre_point(s.position, lanes);
        const MF valid = hn::And(
            lanes.in_row, hn::And(hn::And(hn::Gt(z_eye, hn::Zero(df)), hn::IsFinite(z_eye)), all_finite(p0)));
        store(shadow_pixels(s, b, valid, p0, z_eye, hard0), s.out, lanes);
    }
}

}  // namespace HWY_NAMESPACE
}  // namespace aaf::isg
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include <cstring>
#include <string>

#include "aaf/core/util/error.h"
#include "aaf/core/util/instruction_set.h"
#include "aaf/core/util/parallel.h"

namespace aaf::isg {

HWY_EXPORT(ShadowRow);
HWY_EXPORT(PackShadowRow);

void shadow_row(const ShadowSweep &sweep, int y) {
    (void)instruction_set();  // applies $AAF_ISA before the first dispatch
    HWY_DYNAMIC_DISPATCH(ShadowRow)(sweep, y);
}

namespace {

/// Summed-area table of `flags` (columns x rows) into `table`, a zero row and column first.
void summed_area(const std::vector<unsigned char> &flags, int columns, int rows, std::vector<int> &table) {
    const std::size_t stride = std::size_t(columns) + 1;
    table.assign(stride * (std::size_t(rows) + 1), 0);
    for (std::size_t r = 1; r <= std::size_t(rows); ++r) {
        int row_sum = 0;
        for (std::size_t c = 1; c <= std::size_t(columns); ++c) {
            row_sum += flags[(r - 1) * std::size_t(columns) + c - 1];
            table[r * stride + c] = table[(r - 1) * stride + c] + row_sum;
        }
    }
}

}  // namespace

void prepare_shadow_sweep(ShadowSweep &sweep, ShadowScratch &scratch) {
    (void)instruction_set();
    const PlaneLayout &layout = sweep.layout;
    if (std::ptrdiff_t(layout.width) * layout.height > std::numeric_limits<int>::max() / 8)
        throw Error("an image of " + std::to_string(layout.width) + " x " + std::to_string(layout.height) +
                    " pixels is too large for the ISG methods");
    const std::size_t pixels = std::size_t(layout.width) * std::size_t(layout.height);
    scratch.position_hard.resize(4 * pixels);
    scratch.position_occluder.resize(4 * pixels);
    ShadowTiles &tiles = scratch.tiles;
    constexpr int k = ShadowTiles::kTilePx;
    tiles.columns = (layout.width + k - 1) / k;
    tiles.rows = (layout.height + k - 1) / k;
    const std::size_t count = std::size_t(tiles.columns) * std::size_t(tiles.rows);
    std::vector<unsigned char> in_shadow(count, 0), not_lit(count, 0), not_dark(count, 0);
    const std::uint32_t one_bits = 0x3f800000u;  // 1.0f
    // One tile row per task: its rows packed, then its tiles' flags from the rows just read.
    parallel_for_rows(tiles.rows, [&](int tile_row) {
        const int y_end = std::min(layout.height, (tile_row + 1) * k);
        const std::size_t tiles_at = std::size_t(tile_row) * std::size_t(tiles.columns);
        for (int y = tile_row * k; y < y_end; ++y) {
            HWY_DYNAMIC_DISPATCH(PackShadowRow)(sweep, scratch, y);
            const float *row = sweep.hard + std::ptrdiff_t(y) * layout.row_stride;
            for (int x = 0; x < layout.width; ++x) {
                const float v = row[std::ptrdiff_t(x) * layout.pixel_stride];
                std::uint32_t bits;
                std::memcpy(&bits, &v, sizeof bits);
                const std::size_t tile = tiles_at + std::size_t(x / k);
                in_shadow[tile] |= (v < 0.5f);  // ISG Eq. 6's inShadow, as the search tests it
                not_lit[tile] |= (bits != one_bits);
                not_dark[tile] |= (bits != 0);
            }
        }
    });
    summed_area(in_shadow, tiles.columns, tiles.rows, tiles.in_shadow);
    summed_area(not_lit, tiles.columns, tiles.rows, tiles.not_lit);
    summed_area(not_dark, tiles.columns, tiles.rows, tiles.not_dark);
    sweep.scratch = &scratch;
}

}  // namespace aaf::isg
#endif  // HWY_ONCE
