#include "aaf/core/kernels/sample_statistics.h"

#include "aaf/core/util/error.h"

namespace aaf {

double mean_spp_over_shaded(ConstPlaneView samples_per_pixel, ConstPlaneView object_id) {
    if (samples_per_pixel.width != object_id.width || samples_per_pixel.height != object_id.height)
        throw Error("spp and object id planes differ in size");
    double sum = 0;
    std::size_t shaded = 0;
    for (int y = 0; y < object_id.height; ++y)
        for (int x = 0; x < object_id.width; ++x)
            if (object_id(x, y) != 0) {
                sum += samples_per_pixel(x, y);
                ++shaded;
            }
    return shaded ? sum / double(shaded) : 0.0;
}

}  // namespace aaf
