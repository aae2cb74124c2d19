#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include "aaf/core/util/error.h"
#include "aaf/io/heatmap.h"

#include "../scratch_dir.h"

using namespace aaf;
using aaf_test::scratch_dir;
namespace fs = std::filesystem;

TEST_CASE("heatmap refuses a crop whose x + width overflows int, writing nothing", "[io][heatmap]") {
    const fs::path dir = scratch_dir("heatmap_crop_overflow");
    AovSet a(16, 12), b(16, 12);
    a.add_channel("R", 1.0f);
    b.add_channel("R", 0.5f);
    CompareOptions region;
    region.channels = {"R"};
    for (const PixelRect crop : {PixelRect{2147483600, 0, 100, 10}, PixelRect{0, 2147483600, 10, 100},
                                 PixelRect{8, 0, 2147483600, 10}}) {
        region.crop = crop;
        CHECK_THROWS_WITH(io::write_error_heatmap(a, b, region, (dir / "hm.png").string()),
                          (dir / "hm.png").string() + ": the crop lies outside the image");
    }
    CHECK(fs::is_empty(dir));
}
