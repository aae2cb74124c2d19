#pragma once

// The per-pixel loops of the three ISG methods (Robison and Shirley 2009),
// vectorised with Google Highway and chosen at run time (isg_shadow_rows.cpp, isg_rows.cpp):
// neighbouring pixels of a row share a vector, each lane walking its own
// pixel's taps in the taps' order, sums in float. Every multiply and add is
// rounded on its own (no fused multiply-add), so a pixel's bits depend
// neither on the thread count, nor on the lane count, nor on the
// instruction set.
#include <cstddef>
#include <vector>

#include "aaf/core/contract/plane_view.h"
#include "aaf/core/math/vec3.h"
#include "aaf/core/methods/isg/isg_formulas.h"

namespace aaf::isg {

/// Where a pixel's value lives in every plane a sweep reads: one shared
/// width, height and stride, so one index serves them all.
struct PlaneLayout {
    int width = 0, height = 0;
    int row_stride = 0, pixel_stride = 1;  ///< in floats
};

/// The planes a sweep reads, sharing one layout: the views' own memory when
/// they share one already (the planes of one image, the usual case), else
/// packed copies. The views must have one size; throws aaf::Error for an
/// image too large for int indices.
class SweepPlanes {
  public:
    explicit SweepPlanes(const std::vector<ConstPlaneView> &views);
    const PlaneLayout &layout() const { return layout_; }
    const float *operator[](std::size_t i) const { return data_[i]; }

  private:
    PlaneLayout layout_;
    std::vector<const float *> data_;
    std::vector<std::vector<float>> copies_;
};

/// A tap pattern (tap_set()) as two arrays of offsets in units of the radius.
struct TapArrays {
    std::vector<float> x, y;
    float max_abs_x = 0, max_abs_y = 0;  ///< the largest |x| and |y|: how far a tap reaches
    explicit TapArrays(const std::vector<Tap> &taps);
    int count() const { return int(x.size()); }
};

/// Common settings of a sweep's range weight exp(-(l / scene)^2 / sigma) (ISG Eq. 6-7, 10-11).
struct RangeConstants {
    float inv_scene_size = 1, inv_sigma = 1, max_radius_px = 64;
};

/// Which tiles of kTilePx x kTilePx pixels of the hard visibility hold a
/// pixel in shadow (< 0.5, ISG Eq. 6's inShadow), a pixel other than exactly
/// 1 and a pixel other than exactly +0, as summed-area tables over the tiles
/// ((columns + 1) x (rows + 1), a zero row and column first). A search that
/// reaches no pixel in shadow finds no occluder, and a gather of one value
/// (1 or +0) returns that value whatever its weights, so shadow_row() passes
/// the pixels whose taps stay in such windows over: the same bits, less work.
struct ShadowTiles {
    static constexpr int kTilePx = 4;
    int columns = 0, rows = 0;
    std::vector<int> in_shadow, not_lit, not_dark;
};

/// What prepare_shadow_sweep() derives from a sweep's planes, dense (row
/// after row, 4 floats per pixel): a tap reads one 16-byte quadruple, not
/// four planes.
struct ShadowScratch {
    std::vector<float> position_hard;  ///< (P.x, P.y, P.z, hard V): the gather's
    std::vector<float>
        position_occluder;  ///< (P.x, P.y, P.z, d), d = -1 where the search passes a pixel over
    ShadowTiles tiles;
};

/// isg-shadow (ISG Sec. 3.1, Eq. 4-9) over one row: inputs in `layout`, the
/// filtered visibility written to `out`.
struct ShadowSweep {
    PlaneLayout layout;
    const float *hard = nullptr, *occluder_m = nullptr, *depth_m = nullptr, *position[3] = {};
    const ShadowScratch *scratch = nullptr;  ///< set by prepare_shadow_sweep()
    /// Pass over the blocks ShadowTiles shows need no search or no gather
    /// (false: every pixel computed in full, the same bits, slower).
    bool pass_over_uniform = true;
    const TapArrays *search = nullptr, *gather = nullptr;
    RangeConstants range;
    float light_size_m = 1, focal_px = 1;
    Vec3 light_center;
    PlaneView out;
};
void shadow_row(const ShadowSweep &sweep, int y);
/// Fills `scratch` from `sweep`'s planes in one parallel pass over the rows
/// and points `sweep` at it; throws aaf::Error for an image too large for
/// int indices.
void prepare_shadow_sweep(ShadowSweep &sweep, ShadowScratch &scratch);

/// isg-glossy (ISG Sec. 3.2, Eq. 4, 10-14) over one row.
struct GlossySweep {
    PlaneLayout layout;
    const float *reflection[3] = {}, *reflected_m = nullptr, *theta_max = nullptr, *position[3] = {},
                *normal[3] = {};
    const TapArrays *search = nullptr, *gather = nullptr;
    const float *gather_spatial = nullptr;  ///< the gather's spatial weight per tap
    RangeConstants range;
    float a = 1, b = 1, px_per_rad = 1;
    Vec3 eye;
    PlaneView out[3];
};
void glossy_row(const GlossySweep &sweep, int y);

/// isg-dof (ISG Sec. 3.3, Eq. 4, 15-17) over one row, written to both `out` and `beauty`.
struct DofSweep {
    PlaneLayout layout;
    const float *sharp[3] = {}, *depth_m = nullptr;
    const TapArrays *search = nullptr, *gather = nullptr;
    float max_radius_px = 64, focus_m = 0, coc_inf_px = 0, transition = 0;
    PlaneView out[3], beauty[3];
};
void dof_row(const DofSweep &sweep, int y);

/// Highway's name for the instruction set the rows run with now (e.g. "AVX3").
const char *rows_target();

}  // namespace aaf::isg
