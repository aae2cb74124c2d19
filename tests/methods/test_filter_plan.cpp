// Prepare, then run: a frame's filter plan (prepare_filter) is made once,
// from the frame's channel names and header alone, and it is what the core,
// the file pipeline and `aaf filter` run.
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>
#include <vector>

#include "../cli/run_aaf.h"
#include "../scratch_dir.h"
#include "aaf/core/framework/filter_aovs.h"
#include "aaf/core/framework/method_registry.h"
#include "aaf/core/util/error.h"
#include "aaf/io/exr_io.h"
#include "aaf/io/filter_file.h"
#include "aaf/trace/render.h"

using namespace aaf;
using namespace aaf_test;

namespace {

/// A small combined-effects render: `aaf filter aaf` hands it to maaf6 --pairs 1.
AovSet combined_render() {
    trace::RenderSettings settings;
    settings.width = 24;
    settings.height = 18;
    settings.spp = 4;
    settings.group_parameters.of("maaf6").set("maaf6_effects", std::string("all"));
    settings.aovs = trace::parse_aov_groups("maaf6");
    return trace::render_scene("room", settings);
}

/// `aovs`' channel names and attributes on a 1x1 frame of zeros: no pixel of `aovs`.
AovSet header_of(const AovSet &aovs) {
    AovSet header(1, 1);
    for (const std::string &name : aovs.channel_names()) header.add_channel(name);
    header.attributes = aovs.attributes;
    return header;
}

std::size_t count_of(const std::string &text, const std::string &part) {
    std::size_t count = 0;
    for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++count;
    return count;
}

}  // namespace

TEST_CASE("A filter plan is prepared once per frame and shared by io, the CLI and Python", "[filter_plan]") {
    const AovSet render = combined_render();
    const Method &aaf = find_method("aaf");
    const ParameterSet defaults = aaf.default_parameters();

    // Everything the run needs is decided from the header: the delegate, its
    // parameters, the channels, the note, what is read.
    const FilterPlan plan = prepare_filter(aaf, defaults, header_of(render), ChannelMap{});
    REQUIRE(plan.ready());
    CHECK(plan.asked == &aaf);
    CHECK(plan.method == &find_method("maaf6"));
    CHECK(plan.parameters.text("pairs") == "1");
    CHECK_THAT(plan.note, Catch::Contains("aaf filter maaf6 --pairs 1"));
    CHECK(std::find(plan.input_channels.begin(), plan.input_channels.end(), "maaf6.spp") !=
          plan.input_channels.end());
    const FilterPlan from_pixels = prepare_filter(aaf, defaults, render, ChannelMap{});
    CHECK(from_pixels.method == plan.method);
    CHECK(from_pixels.note == plan.note);
    CHECK(from_pixels.input_channels == plan.input_channels);

    // Run on the pixels, the header's plan gives filter_aovs()' bytes.
    const AovSet direct = filter_aovs(aaf, render, ChannelMap{}, defaults);
    const AovSet planned = run_filter(plan, render);
    REQUIRE(planned.channel_names() == direct.channel_names());
    for (const std::string &name : direct.channel_names()) {
        INFO(name);
        CHECK(planned.plane(planned.index_of(name)) == direct.plane(direct.index_of(name)));
    }

    // The file pipeline prepares once per frame, and its note and scrubbing are the plan's.
    const fs::path dir = aaf_test::scratch_dir("filter_plan");
    const std::string input = (dir / "combined.exr").string(), output = (dir / "out.exr").string();
    io::write_aovs(render, input);
    io::FrameFilter filter = io::method_filter(aaf, defaults, ChannelMap{});
    int prepared = 0;
    filter.prepare = [&prepared, prepare = filter.prepare](const AovSet &frame) {
        ++prepared;
        return prepare(frame);
    };
    const io::FilterFileReport report = io::filter_file(input, output, filter);
    CHECK(prepared == 1);
    CHECK(report.notes == std::vector<std::string>{input + ": " + plan.note});
    const AovSet written = io::read_aovs(output);
    CHECK(written.plane(written.index_of("R")) == direct.plane(direct.index_of("R")));
    io::filter_file(input, output, filter);
    CHECK(prepared == 2);  // the next frame, its own plan

    // `aaf filter` reports that one plan's note once and writes its pixels.
    const std::string cli_output = (dir / "cli.exr").string();
    const RunResult cli = run_aaf("filter aaf " + input + " -o " + cli_output);
    REQUIRE(cli.exit_code == 0);
    CHECK(count_of(cli.output, "aaf: note: ") == 1);
    CHECK_THAT(cli.output, Catch::Contains(plan.note));
    const AovSet from_cli = io::read_aovs(cli_output);
    CHECK(from_cli.plane(from_cli.index_of("R")) == direct.plane(direct.index_of("R")));

    // A frame without the whole maaf6 layer: AAF's own plan, which lists what
    // it lacks and is refused by the run, naming the first.
    AovSet partial = render;
    (void)partial.take_channel("maaf6.spp");
    const FilterPlan lacking = prepare_filter(aaf, defaults, header_of(partial), ChannelMap{});
    CHECK(lacking.method == &aaf);
    CHECK_FALSE(lacking.ready());
    CHECK(lacking.note.empty());
    CHECK_THROWS_AS(run_filter(lacking, partial), InputError);
    CHECK_THROWS_WITH(run_filter(lacking, partial), Catch::Contains("AAF") && Catch::Contains("unshadowed"));

    // A plan runs only on a frame that has what it was prepared for.
    AovSet other(24, 18);
    for (const char *name : {"R", "G", "B"}) other.add_channel(name, 0.5f);
    CHECK_THROWS_WITH(run_filter(plan, other), Catch::Contains("prepared for another frame"));
}
