#include "aaf/core/occluder_fill.h"

#include <algorithm>
#include <vector>

#include "aaf/core/parallel.h"

namespace aaf {

FilledOccluders fill_occluder_distances(ConstPlaneView d2_min, ConstPlaneView d2_max,
                                        ConstPlaneView object_id, int radius_px) {
    const int width = d2_max.width, height = d2_max.height;
    FilledOccluders filled;
    filled.d2_min_m.assign(std::size_t(width) * height, 0.0f);
    filled.d2_max_m.assign(std::size_t(width) * height, 0.0f);
    const int r = radius_px;
    // Summed-area table of occluded pixels: most unoccluded pixels have none in
    // their window, and skip the search.
    std::vector<int> occluded_before((std::size_t(width) + 1) * (height + 1), 0);
    const std::size_t sat_width = std::size_t(width) + 1;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            occluded_before[(y + 1) * sat_width + x + 1] =
                int(has_occluder(d2_max(x, y))) + occluded_before[y * sat_width + x + 1] +
                occluded_before[(y + 1) * sat_width + x] - occluded_before[y * sat_width + x];
    auto occluded_in_window = [&](int x0, int y0, int x1, int y1) {  // inclusive bounds
        return occluded_before[(y1 + 1) * sat_width + x1 + 1] - occluded_before[y0 * sat_width + x1 + 1] -
               occluded_before[(y1 + 1) * sat_width + x0] + occluded_before[y0 * sat_width + x0];
    };

    parallel_for_rows(height, [&](int y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t i = std::size_t(y) * width + x;
            if (has_occluder(d2_max(x, y))) {
                filled.d2_min_m[i] = d2_min(x, y);
                filled.d2_max_m[i] = d2_max(x, y);
                continue;
            }
            const int x0 = std::max(0, x - r), x1 = std::min(width - 1, x + r);
            const int y0 = std::max(0, y - r), y1 = std::min(height - 1, y + r);
            if (occluded_in_window(x0, y0, x1, y1) == 0) continue;
            const float id = object_id(x, y);
            double sum_min = 0, sum_max = 0;
            int count = 0;
            for (int ny = y0; ny <= y1; ++ny)
                for (int nx = x0; nx <= x1; ++nx) {
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
