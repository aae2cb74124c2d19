// filter_file(): one frame file to file, with a toy filter in place of a
// method, so the promises of the pipeline are checked apart from any filter.
#include <catch2/catch.hpp>

#include <OpenImageIO/imageio.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <stdexcept>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/thread_count.h"
#include "aaf/io/exr_io.h"
#include "aaf/io/filter_file.h"

#include "../scratch_dir.h"

using namespace aaf;
using aaf_test::scratch_dir;
namespace fs = std::filesystem;

namespace {

constexpr int kWidth = 7, kHeight = 5;

std::string file_bytes(const fs::path &path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::size_t file_count(const fs::path &dir) {
    return std::size_t(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

/// A frame with a beauty, the toy filter's input `toy.in` (x + 10 y) and a
/// channel no filter reads.
AovSet toy_frame() {
    AovSet aovs(kWidth, kHeight);
    for (const char *name : {"R", "G", "B"}) aovs.add_channel(name, 0.5f);
    PlaneView in = aovs.add_channel("toy.in"), other = aovs.add_channel("other.X");
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            in(x, y) = float(x + 10 * y);
            other(x, y) = -float(x);
        }
    aovs.attributes["studio:shot"] = std::string("sq010");
    return aovs;
}

/// The toy filter: keeps its input and adds toy.out = 2 toy.in, row by row on
/// the current arena; records the arena's concurrency when asked.
io::FrameFilter doubling_filter(int *concurrency = nullptr) {
    io::FrameFilter filter;
    filter.candidate_channels = [](const AovSet &) { return std::vector<std::string>{"toy.in"}; };
    filter.prepare = [](const AovSet &) {
        FilterPlan plan;
        plan.input_channels = {"toy.in"};
        return plan;
    };
    filter.run = [concurrency](const FilterPlan &, const AovSet &input) {
        if (concurrency) *concurrency = tbb::this_task_arena::max_concurrency();
        AovSet output = input;
        const ConstPlaneView in = input.channel("toy.in");
        PlaneView out = output.add_channel("toy.out");
        tbb::parallel_for(0, input.height(), [&](int y) {
            for (int x = 0; x < input.width(); ++x) out(x, y) = 2 * in(x, y);
        });
        return output;
    };
    return filter;
}

/// Writes `aovs` as part 0 (with a matrix attribute AovSet cannot hold) and
/// the channels `toy.in` plus `extra.u` as part 1 ("extra"), as renderers
/// that write one AOV per part do.
void write_two_parts(const fs::path &path, const AovSet &aovs, const AovSet::Plane &toy_in) {
    using OIIO::TypeDesc;
    OIIO::ImageSpec first(kWidth, kHeight, int(aovs.channel_names().size()), TypeDesc::FLOAT);
    first.channelnames = aovs.channel_names();
    first.attribute("name", "rgba");
    const float matrix[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1.5f, -2, 3, 1};
    first.attribute("worldToCamera", OIIO::TypeMatrix44, matrix);
    OIIO::ImageSpec second(kWidth, kHeight, 2, TypeDesc::FLOAT);
    second.channelnames = {"extra.u", "toy.in"};
    second.attribute("name", "extra");
    std::vector<float> first_pixels, second_pixels;
    for (std::size_t i = 0; i < aovs.pixel_count(); ++i) {
        for (std::size_t c = 0; c < aovs.channel_names().size(); ++c)
            first_pixels.push_back(aovs.plane(c)[i]);
        second_pixels.insert(second_pixels.end(), {0.25f * float(i), toy_in[i]});
    }
    const OIIO::ImageSpec specs[2] = {first, second};
    auto out = OIIO::ImageOutput::create("openexr");
    REQUIRE(out->open(path.string(), 2, specs));
    REQUIRE(out->write_image(TypeDesc::FLOAT, first_pixels.data()));
    REQUIRE(out->open(path.string(), second, OIIO::ImageOutput::AppendSubimage));
    REQUIRE(out->write_image(TypeDesc::FLOAT, second_pixels.data()));
    REQUIRE(out->close());
}

}  // namespace

TEST_CASE("filter_file writes the filter's output and never modifies the input", "[io][filter_file]") {
    const fs::path dir = scratch_dir("filter_file_basic");
    const std::string input = (dir / "in.exr").string(), output = (dir / "out.exr").string();
    io::write_aovs(toy_frame(), input);
    const std::string before = file_bytes(input);

    const io::FilterFileReport report = io::filter_file(input, output, doubling_filter());
    CHECK(report.warnings.empty());
    CHECK(report.borrowed.empty());
    CHECK(file_bytes(input) == before);
    const AovSet out = io::read_aovs(output);
    CHECK(out.channel("toy.out")(3, 2) == 2 * 23.0f);
    CHECK(out.channel("other.X")(4, 0) == -4.0f);
    CHECK(std::get<std::string>(out.attributes.at("studio:shot")) == "sq010");

    // Writing over the input is refused before anything is read or written.
    CHECK_THROWS_AS(io::filter_file(input, input, doubling_filter()), InputError);
    CHECK(file_bytes(input) == before);
}

TEST_CASE("filter_file: a failing filter leaves no output, no temporary, an older output untouched",
          "[io][filter_file]") {
    const fs::path dir = scratch_dir("filter_file_fails");
    const std::string input = (dir / "in.exr").string(), output = (dir / "out.exr").string();
    io::write_aovs(toy_frame(), input);
    io::FrameFilter failing = doubling_filter();
    failing.run = [](const FilterPlan &, const AovSet &) -> AovSet {
        throw InputError("missing channel 'toy.d1'");
    };

    // The error names the file and keeps its kind (the CLI's exit code).
    CHECK_THROWS_AS(io::filter_file(input, output, failing), InputError);
    CHECK_THROWS_WITH(io::filter_file(input, output, failing),
                      Catch::StartsWith(input + ": ") && Catch::Contains("toy.d1"));
    CHECK(file_count(dir) == 1);

    std::ofstream(output) << "an older output";
    CHECK_THROWS(io::filter_file(input, output, failing));
    CHECK(file_bytes(output) == "an older output");
    CHECK(file_count(dir) == 2);
}

TEST_CASE("filter_file: other parts and header attributes go through, borrowed channels stay in their part",
          "[io][filter_file]") {
    const fs::path dir = scratch_dir("filter_file_parts");
    const std::string input = (dir / "in.exr").string(), output = (dir / "out.exr").string();
    AovSet first = toy_frame();
    const AovSet::Plane toy_in = first.plane(first.index_of("toy.in"));
    AovSet without_toy(kWidth, kHeight);
    for (const std::string &name : first.channel_names())
        if (name != "toy.in")
            std::copy(first.plane(first.index_of(name)).begin(), first.plane(first.index_of(name)).end(),
                      without_toy.add_channel(name).data);
    write_two_parts(input, without_toy, toy_in);

    const io::FilterFileReport report = io::filter_file(input, output, doubling_filter());
    CHECK(report.borrowed == std::vector<std::string>{"toy.in"});

    auto in = OIIO::ImageInput::open(output);
    REQUIRE(in);
    const OIIO::ImageSpec part0 = in->spec(0, 0), part1 = in->spec(1, 0);
    CHECK(part0.channelindex("toy.out") >= 0);
    CHECK(part0.channelindex("toy.in") < 0);  // read for the filter, not duplicated
    const OIIO::ParamValue *matrix = part0.find_attribute("worldToCamera", OIIO::TypeMatrix44);
    REQUIRE(matrix);
    CHECK(static_cast<const float *>(matrix->data())[12] == 1.5f);
    CHECK(part1.get_string_attribute("name") == "extra");
    CHECK(part1.channelindex("toy.in") >= 0);
    CHECK(part1.channelindex("extra.u") >= 0);
    const AovSet out = io::read_aovs(output);
    CHECK(out.channel("toy.out")(6, 4) == 2 * 46.0f);
}

TEST_CASE("filter_file: NaN/Inf in the filter's inputs are replaced and counted, other channels kept",
          "[io][filter_file]") {
    const fs::path dir = scratch_dir("filter_file_nan");
    const std::string input = (dir / "in.exr").string(), output = (dir / "out.exr").string();
    AovSet aovs = toy_frame();
    aovs.channel("toy.in")(1, 1) = std::numeric_limits<float>::quiet_NaN();
    aovs.channel("toy.in")(2, 1) = -std::numeric_limits<float>::infinity();
    aovs.channel("other.X")(0, 0) = std::numeric_limits<float>::quiet_NaN();  // not read by the filter
    io::write_aovs(aovs, input);

    const io::FilterFileReport report = io::filter_file(input, output, doubling_filter());
    CHECK(report.non_finite == NonFiniteCounts{{"toy.in", 2}});
    REQUIRE(report.warnings.size() == 1);
    CHECK(report.warnings[0] == input + ": replaced 2 NaN/Inf input values by 0 (toy.in 2)");
    const AovSet out = io::read_aovs(output);
    CHECK(out.channel("toy.out")(1, 1) == 0.0f);
    CHECK(out.channel("toy.out")(2, 1) == 0.0f);
    CHECK(std::isnan(out.channel("other.X")(0, 0)));

    io::FilterFileOptions keep_nan;
    keep_nan.replace_non_finite = false;
    const io::FilterFileReport untouched = io::filter_file(input, output, doubling_filter(), keep_nan);
    CHECK(untouched.warnings.empty());
    CHECK(std::isnan(io::read_aovs(output).channel("toy.out")(1, 1)));
}

TEST_CASE(
    "filter_file: a thin-lens input recomposed (--compose paper) gets a warning naming it and the method "
    "that drops its defocus",
    "[io][filter_file]") {
    const fs::path dir = scratch_dir("filter_file_lens");
    const std::string input = (dir / "in.exr").string(), output = (dir / "out.exr").string();
    AovSet aovs = toy_frame();
    aovs.attributes[attr::kApertureRadius] = 0.01f;
    io::write_aovs(aovs, input);
    io::FrameFilter composing = doubling_filter();
    composing.composes_beauty = "toy";
    // Corrected, such a beauty is kept (the method's note says so): no warning.
    CHECK(io::filter_file(input, output, composing).warnings.empty());
    const auto prepare = composing.prepare;
    composing.prepare = [prepare](const AovSet &frame) {
        FilterPlan plan = prepare(frame);
        plan.composition = Composition::Paper;
        return plan;
    };
    const io::FilterFileReport report = io::filter_file(input, output, composing);
    REQUIRE(report.warnings.size() == 1);
    CHECK_THAT(report.warnings[0], Catch::StartsWith(input + ": rendered through a thin lens; toy filters"));
    // A filter that leaves the beauty alone (a defocus filter, say) has nothing to warn about.
    CHECK(io::filter_file(input, output, doubling_filter()).warnings.empty());
}

TEST_CASE("filter_file: keep_beauty leaves R,G,B as they were and adds the filtered image as aaf.R/G/B",
          "[io][filter_file]") {
    const fs::path dir = scratch_dir("filter_file_keep");
    const std::string input = (dir / "in.exr").string(), output = (dir / "out.exr").string();
    io::write_aovs(toy_frame(), input);
    // As a method does: the beauty becomes the filtered image, the input's kept as noisy.R/G/B.
    io::FrameFilter brighten = doubling_filter();
    brighten.run = [](const FilterPlan &, const AovSet &input) {
        AovSet output = input;
        for (const char *c : {"R", "G", "B"}) {
            std::copy(input.plane(input.index_of(c)).begin(), input.plane(input.index_of(c)).end(),
                      output.add_channel(std::string("noisy.") + c).data);
            output.channel(c)(0, 0) = 2.0f;
        }
        return output;
    };
    io::FilterFileOptions options;
    options.keep_beauty = true;
    io::filter_file(input, output, brighten, options);

    const AovSet out = io::read_aovs(output);
    CHECK(out.channel("R")(0, 0) == 0.5f);
    CHECK(out.channel("aaf.R")(0, 0) == 2.0f);
    CHECK(out.channel("aaf.B")(1, 0) == 0.5f);
    CHECK_FALSE(out.has_channel("noisy.R"));
    CHECK(out.has_channel("other.X"));
}

TEST_CASE("filter_file: 1 and 3 threads give identical bytes, each run on its arena", "[io][filter_file]") {
    const fs::path dir = scratch_dir("filter_file_threads");
    const std::string input = (dir / "in.exr").string();
    io::write_aovs(toy_frame(), input);
    std::string bytes[2];
    const int threads[2] = {1, 3};
    for (int i = 0; i < 2; ++i) {
        io::FilterFileOptions options;
        options.threads = threads[i];
        int concurrency = 0;
        const fs::path output = dir / ("out" + std::to_string(threads[i]) + ".exr");
        io::filter_file(input, output.string(), doubling_filter(&concurrency), options);
        CHECK(concurrency == threads[i]);
        bytes[i] = file_bytes(output);
    }
    CHECK(bytes[0] == bytes[1]);

    io::FilterFileOptions negative;
    negative.threads = -1;
    CHECK_THROWS_AS(io::filter_file(input, (dir / "bad.exr").string(), doubling_filter(), negative), Error);
}
