#include "aaf/core/occluder_fill.h"

#include <algorithm>

#include "aaf/core/parallel.h"

namespace aaf {

FilledOccluders fill_occluder_distances(ConstPlaneView d2_min, ConstPlaneView d2_max, ConstPlaneView object_id,
                                        int radius_px) {
    const int width = d2_max.width, height = d2_max.height;
    FilledOccluders filled;
    filled.d2_min_m.assign(std::size_t(width) * height, 0.0f);
    filled.d2_max_m.assign(std::size_t(width) * height, 0.0f);
    const int r = radius_px;
    parallel_for_rows(height, [&](int y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t i = std::size_t(y) * width + x;
            if (has_occluder(d2_max(x, y))) {
                filled.d2_min_m[i] = d2_min(x, y);
                filled.d2_max_m[i] = d2_max(x, y);
                continue;
            }
            const float id = object_id(x, y);
            double sum_min = 0, sum_max = 0;
            int count = 0;
            for (int ny = std::max(0, y - r); ny <= std::min(height - 1, y + r); ++ny)
                for (int nx = std::max(0, x - r); nx <= std::min(width - 1, x + r); ++nx) {
                    if ((nx - x) * (nx - x) + (ny - y) * (ny - y) > r * r) continue;
                    if (object_id(nx, ny) != id || !has_occluder(d2_max(nx, ny))) continue;
                    sum_min += d2_min(nx, ny);
                    sum_max += d2_max(nx, ny);
                    ++count;
                }
            if (count > 0) {
                filled.d2_min_m[i] = float(sum_min / count);
                filled.d2_max_m[i] = float(sum_max / count);
            }
        }
    });
    return filled;
}

}  // namespace aaf
