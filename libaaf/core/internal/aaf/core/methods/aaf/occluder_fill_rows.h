#pragma once

#include <cstddef>

namespace aaf::detail {

/// The search of AAF Sec. 6's occluder fill (occluder_fill.h) over one row:
/// padded row-major planes of image rows first_row, first_row + 1, ..., `pad`
/// columns of padding left of each row and at least pad +
/// kOccluderSearchPadding right of it.
struct OccluderSearch {
    /// Per pixel, the id a neighbour must match to lend its distances: the
    /// object's id where occluded, NaN (matching nothing) elsewhere and in the padding.
    const float *lender_id = nullptr;
    const float *d2_min_m = nullptr, *d2_max_m = nullptr;
    std::size_t padded_width = 0;
    int pad = 0, width = 0, height = 0;
    /// The image row the planes' first row holds; rows within `pad` of a searched row must be there.
    int first_row = 0;
    /// The disc: row dy (|dy| <= pad) spans dx in [-half_width[|dy|], half_width[|dy|]].
    const int *half_width = nullptr;
    /// Per row (from first_row, `near_stride` bytes apart) and column x: 1
    /// where an occluded pixel lies in columns [x - pad, x + pad] of that row,
    /// 0 elsewhere and in at least kOccluderSearchPadding bytes past the row,
    /// so a vector of centres skips rows that hold no lender for any of them.
    const unsigned char *occluded_near = nullptr;
    std::size_t near_stride = 0;
};

/// Columns of padding, beyond the disc's, that rows and centre ids need on the right.
inline constexpr int kOccluderSearchPadding = 16;

/// For every pixel x of row `y` whose `centre_id[x]` is not NaN: the mean
/// d2min and d2max over the disc's lenders of that id, summed in float row
/// by row, left to right, written to out_*[x] where there is at least one
/// lender (others untouched). `centre_id` holds width + kOccluderSearchPadding
/// entries, NaN past the row. Vectorised over neighbouring centres with
/// Google Highway's runtime dispatch; every instruction set gives the same bits.
void search_occluder_row(const OccluderSearch &search, int y, const float *centre_id, float *out_d2_min_m,
                         float *out_d2_max_m);

}  // namespace aaf::detail
