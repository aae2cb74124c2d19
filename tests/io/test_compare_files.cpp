// compare_files() and its batch summaries, apart from how `aaf compare` prints them.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "aaf/core/util/error.h"
#include "aaf/io/compare_files.h"
#include "aaf/io/exr_io.h"

#include "../scratch_dir.h"

using namespace aaf;
using aaf_test::scratch_dir;
namespace fs = std::filesystem;

namespace {

/// An 8x6 image: R,G,B a ramp plus `offset`, and a shadow layer of two channels.
AovSet ramp(float offset, int width = 8, int height = 6) {
    AovSet aovs(width, height);
    for (const char *name : {"R", "G", "B", "shadow.V", "shadow.W"}) {
        PlaneView plane = aovs.add_channel(name);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) plane(x, y) = 0.05f * float(x + y) + offset;
    }
    return aovs;
}

const io::CompareMetric &metric(const std::string &key) {
    const io::CompareMetric *m = io::find_compare_metric(key);
    REQUIRE(m);
    return *m;
}

/// Results carrying only `values` of `key` (and the labels a, b, c, ...).
std::vector<io::ComparePairResult> results_with(const std::string &key, const std::vector<double> &values) {
    std::vector<io::ComparePairResult> results;
    for (double v : values) {
        io::ComparePairResult r;
        r.pair.label = std::string(1, char('a' + results.size()));
        r.metrics.*(metric(key).value) = v;
        results.push_back(r);
    }
    return results;
}

}  // namespace

TEST_CASE("compare_files: identical images have RMSE 0 and infinite PSNR", "[io][compare]") {
    const fs::path dir = scratch_dir("compare_identical");
    const std::string a = (dir / "a.exr").string(), b = (dir / "b.exr").string();
    io::write_aovs(ramp(0), a);
    io::write_aovs(ramp(0), b);
    io::CompareFilesOptions options;
    options.metrics = {&metric("rmse"), &metric("psnr")};
    const io::CompareFilesResult result = io::compare_files({{"a", a, b}}, options);
    REQUIRE(result.pairs.size() == 1);
    const io::ComparePairResult &r = result.pairs[0];
    CHECK(r.metrics.rmse == 0.0);
    CHECK(std::isinf(r.metrics.psnr));
    CHECK(r.metrics.pixels == 48);
    CHECK(r.channels == std::vector<std::string>{"R", "G", "B"});
    CHECK(std::isnan(r.spp));           // no spp or object-id AOVs
    CHECK(std::isnan(r.metrics.ssim));  // not asked for
}

TEST_CASE("compare_files: a layer selects its channels and SSIM runs when asked for", "[io][compare]") {
    const fs::path dir = scratch_dir("compare_layer");
    const std::string a = (dir / "a.exr").string(), b = (dir / "b.exr").string();
    io::write_aovs(ramp(0.1f), a);
    io::write_aovs(ramp(0), b);
    io::CompareFilesOptions options;
    options.layer = "shadow";
    options.metrics = {&metric("ssim")};
    const io::CompareFilesResult result = io::compare_files({{"a", a, b}}, options);
    CHECK(result.pairs[0].channels == std::vector<std::string>{"shadow.V", "shadow.W"});
    CHECK(result.pairs[0].metrics.mae == Approx(0.1));
    CHECK(std::isfinite(result.pairs[0].metrics.ssim));

    options.layer = "nothing";
    CHECK_THROWS_AS(io::compare_files({{"a", a, b}}, options), InputError);
    CHECK_THROWS_WITH(io::compare_files({{"a", a, b}}, options),
                      Catch::StartsWith(a + ": ") && Catch::Contains("'nothing'"));
}

TEST_CASE("compare_files: a crop outside the image is an error naming the pair and the crop",
          "[io][compare]") {
    const fs::path dir = scratch_dir("compare_crop");
    const std::string a = (dir / "a.exr").string(), b = (dir / "b.exr").string();
    io::write_aovs(ramp(0.1f), a);
    io::write_aovs(ramp(0), b);
    io::CompareFilesOptions options;
    options.crop = PixelRect{6, 0, 4, 2};
    CHECK_THROWS_WITH(io::compare_files({{"a", a, b}}, options),
                      Catch::StartsWith(a + " vs " + b + ": ") && Catch::Contains("crop 4x2+6+0"));
    options.crop = PixelRect{4, 2, 4, 4};  // inside: only those pixels count
    CHECK(io::compare_files({{"a", a, b}}, options).pairs[0].metrics.pixels == 16);
}

TEST_CASE("compare_files: the mask selects pixels and must match the images' size", "[io][compare]") {
    const fs::path dir = scratch_dir("compare_mask");
    const std::string a = (dir / "a.exr").string(), b = (dir / "b.exr").string();
    const std::string mask = (dir / "mask.exr").string(), small = (dir / "small.exr").string();
    io::write_aovs(ramp(0.1f), a);
    io::write_aovs(ramp(0), b);
    AovSet m(8, 6);
    m.add_channel("Y");
    m.channel("Y")(2, 3) = 1;
    m.channel("Y")(5, 1) = 1;
    io::write_aovs(m, mask);
    io::write_aovs(ramp(0, 4, 4), small);

    io::CompareFilesOptions options;
    options.mask = io::read_compare_mask(mask);
    CHECK(options.mask->channel == "Y");
    CHECK(io::compare_files({{"a", a, b}}, options).pairs[0].metrics.pixels == 2);
    CHECK_THROWS_WITH(io::read_compare_mask(mask, "Z"), Catch::StartsWith(mask + ": no channel 'Z'"));

    options.mask = io::read_compare_mask(small);
    CHECK_THROWS_AS(io::compare_files({{"a", a, b}}, options), InputError);
    CHECK_THROWS_WITH(io::compare_files({{"a", a, b}}, options),
                      Catch::StartsWith(small + ": the mask is 4x4"));
}

TEST_CASE("compare_files: no output may replace an input and a heatmap needs one pair", "[io][compare]") {
    const fs::path dir = scratch_dir("compare_outputs");
    const std::string a = (dir / "a.exr").string(), b = (dir / "b.exr").string();
    io::write_aovs(ramp(0.1f), a);
    io::write_aovs(ramp(0), b);
    io::CompareFilesOptions options;
    options.report_paths = {b};
    CHECK_THROWS_AS(io::compare_files({{"a", a, b}}, options), InputError);

    options.report_paths.clear();
    options.heatmap = (dir / "heat.png").string();
    CHECK_THROWS_AS(io::compare_files({{"a", a, b}, {"b", b, a}}, options), Error);
    const io::CompareFilesResult result = io::compare_files({{"a", a, b}}, options);
    CHECK(result.heatmap_scale > 0);
    CHECK(fs::exists(dir / "heat.png"));
    CHECK(fs::exists(dir / "heat.exr"));
}

TEST_CASE("summarise: mean, median and the worst pair, lower or higher being better", "[io][compare]") {
    const std::vector<io::ComparePairResult> rmse = results_with("rmse", {3, 1, 10, 2});
    const io::MetricSummary errors = io::summarise(rmse, metric("rmse"));
    CHECK(errors.mean == Approx(4.0));
    CHECK(errors.median == Approx(2.5));  // even count: the mean of the middle two
    CHECK(errors.worst == 10.0);
    CHECK(rmse[errors.worst_index].pair.label == "c");

    const std::vector<io::ComparePairResult> psnr = results_with("psnr", {30, 20, 40});
    const io::MetricSummary quality = io::summarise(psnr, metric("psnr"));
    CHECK(quality.median == 30.0);
    CHECK(quality.worst == 20.0);  // higher is better: the worst is the lowest
    CHECK(quality.worst_index == 1);

    // Ties keep the first pair.
    CHECK(io::summarise(results_with("mae", {5, 5}), metric("mae")).worst_index == 0);
    CHECK_THROWS_AS(io::summarise({}, metric("rmse")), Error);
}

TEST_CASE("failed_gates: each pair over (or under) a limit, and NaN, fails", "[io][compare]") {
    const std::vector<io::ComparePairResult> results =
        results_with("rmse", {0.1, 0.5, std::numeric_limits<double>::quiet_NaN()});
    const std::vector<io::GateFailure> above = io::failed_gates(results, {{&metric("rmse"), 0.2, true}});
    REQUIRE(above.size() == 2);
    CHECK(above[0].pair_index == 1);
    CHECK(above[0].value == 0.5);
    CHECK(above[1].pair_index == 2);
    const std::vector<io::GateFailure> below = io::failed_gates(results, {{&metric("rmse"), 0.2, false}});
    REQUIRE(below.size() == 2);
    CHECK(below[0].pair_index == 0);
    CHECK(io::find_compare_metric("nope") == nullptr);
}
