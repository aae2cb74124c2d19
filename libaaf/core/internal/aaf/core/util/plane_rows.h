#pragma once

#include <cstddef>
#include <vector>

#include "aaf/core/contract/plane_view.h"

namespace aaf {

/// Row y of `view` as contiguous floats, for loops that run along a row in
/// vector lanes: the view's own memory where its pixels are adjacent, else a
/// copy in `buffer`.
inline const float *contiguous_row(ConstPlaneView view, int y, std::vector<float> &buffer) {
    const float *first = view.data + std::ptrdiff_t(y) * view.row_stride;
    if (view.pixel_stride == 1) return first;
    buffer.resize(std::size_t(view.width));
    for (int x = 0; x < view.width; ++x)
        buffer[std::size_t(x)] = first[std::ptrdiff_t(x) * view.pixel_stride];
    return buffer.data();
}

}  // namespace aaf
