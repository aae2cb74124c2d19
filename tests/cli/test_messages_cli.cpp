// What a user who mistypes a name or feeds the wrong file reads: one line
// naming the file (or option) and the problem, with the name they meant.

#include <OpenImageIO/imageio.h>

#include <catch2/catch.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "aaf/core/contract/aov_set.h"
#include "aaf/io/exr_io.h"
#include "aaf/trace/render.h"
#include "flat_image.h"
#include "run_aaf.h"

namespace {

using aaf_test::run_aaf;
using aaf_test::scratch_dir;
namespace fs = std::filesystem;

constexpr int kWidth = 32, kHeight = 24;

aaf::AovSet small_render() {
    aaf::trace::RenderSettings settings;
    settings.width = kWidth;
    settings.height = kHeight;
    settings.spp = 4;
    return aaf::trace::render_scene("grids", settings);
}

/// `render` as Blender names a multilayer EXR's passes (ViewLayer.Combined.R,
/// ViewLayer.Position.X, ViewLayer.IndexOB.X) with every object's pass index
/// left at 0 (Blender's default), the contract's other AOVs under the view
/// layer; with `tracer_ids`, also the tracer's own ids as
/// scripts/blender/aaf_complete.py adds them (ViewLayer.id.object).
aaf::AovSet blender_file(const aaf::AovSet &render, bool tracer_ids) {
    aaf::AovSet blender(render.width(), render.height());
    blender.attributes = render.attributes;
    const std::string layer = "ViewLayer.";
    for (std::size_t c = 0; c < render.channel_names().size(); ++c) {
        const std::string &name = render.channel_names()[c];
        std::string renamed = layer + name;
        if (name == "R" || name == "G" || name == "B") renamed = layer + "Combined." + name;
        if (name.rfind("P.", 0) == 0) renamed = layer + "Position." + name.substr(2);
        if (name.rfind("N.", 0) == 0) renamed = layer + "Normal." + name.substr(2);
        if (name == "id.object") {
            blender.add_channel(layer + "IndexOB.X", 0.0f);
            if (!tracer_ids) continue;
        }
        aaf::PlaneView plane = blender.add_channel(renamed);
        std::copy(render.plane(c).begin(), render.plane(c).end(), plane.data);
    }
    return blender;
}

void write_png(const fs::path &path) {
    auto out = OIIO::ImageOutput::create(path.string());
    REQUIRE(out);
    const OIIO::ImageSpec spec(4, 4, 3, OIIO::TypeDesc::UINT8);
    const std::vector<unsigned char> pixels(4 * 4 * 3, 128);
    REQUIRE(out->open(path.string(), spec));
    REQUIRE(out->write_image(OIIO::TypeDesc::UINT8, pixels.data()));
    REQUIRE(out->close());
}

std::vector<std::string> lines_of(const std::string &text) {
    std::vector<std::string> lines;
    std::istringstream stream(text);
    for (std::string line; std::getline(stream, line);) lines.push_back(line);
    return lines;
}

/// One command: the exit code it must give and a text the one line it
/// prints about it must hold (an error, or a warning when it succeeds;
/// empty: it prints nothing).
struct Row {
    std::string args;
    int exit_code;
    std::string line;
};

}  // namespace

TEST_CASE("CLI: a mistyped name or a wrong file gets one line naming it, what was meant and the fix",
          "[cli][messages]") {
    const fs::path dir = scratch_dir("messages");
    const aaf::AovSet render = small_render();
    const std::string contract = (dir / "contract.exr").string(), unset = (dir / "blender.exr").string(),
                      png = (dir / "picture.png").string(), beauty = (dir / "beauty.exr").string(),
                      output = (dir / "out.exr").string(), out = " -o " + output;
    aaf::io::write_aovs(render, contract);
    aaf::io::write_aovs(blender_file(render, /*tracer_ids=*/false), unset);
    write_png(png);
    aaf_test::write_flat(beauty, 0.5f);
    const std::string arnold = (dir / "arnold.exr").string();  // Arnold's beauty AOV
    aaf::AovSet rgba(4, 4);
    for (const char *name : {"RGBA.R", "RGBA.G", "RGBA.B", "RGBA.A"}) rgba.add_channel(name, 0.5f);
    aaf::io::write_aovs(rgba, arnold);

    const std::vector<Row> rows = {
        {"fliter aaf " + contract + out, 2,
         "unknown command 'fliter' (render, plan, filter, compare, info, "
         "preview, analyze); did you mean 'filter'?"},
        {"filter aff " + contract + out, 2, "unknown method 'aff' ("},
        {"filter aff " + contract + out, 2, "); did you mean 'aaf'?"},
        {"filter AAF " + contract + out, 2, "did you mean 'aaf'?"},
        {"filter aaf " + contract + out + " --normal-treshold 30", 2,
         "--normal-treshold; did you mean '--normal-threshold'?"},
        {"filter aaf " + contract + out + " --map visiblity=shadow.V", 2, "did you mean 'visibility'?"},
        {"filter aaf " + contract + out + " --map visibility=shadow.v", 3,
         "contract.exr: no such channel 'shadow.v' (--map visibility=shadow.v); did you mean 'shadow.V'?"},
        {"filter aaf " + png + out, 3,
         "picture.png: not an AOV EXR (a 4x4 PNG image with channels R, G, B, none of them an AOV"},
        {"filter gaussian " + beauty + out, 3,
         "beauty.exr: not an AOV EXR (a 4x4 OpenEXR image with channels R, G, B, none of them an AOV"},
        {"filter aaf " + unset + out, 0,
         "blender.exr: object id channel 'ViewLayer.IndexOB.X' is 0 everywhere, so every pixel counts as "
         "background and nothing is filtered; set each object's pass index in Blender"},
        {"filter aaf " + unset + out, 0,
         "blender.exr: AAF changed nothing: ViewLayer.aaf.V equals ViewLayer.shadow.V at every pixel"},
        {"preview " + unset + " -o " + (dir / "blender.png").string(), 0, ""},
        {"preview " + arnold + " -o " + (dir / "arnold.png").string(), 0, ""},
        {"preview " + contract + " --channels shadow.v -o " + (dir / "v.png").string(), 3,
         "contract.exr: no channel 'shadow.v' to preview (it has "},
        {"preview " + contract + " --channels shadow.v -o " + (dir / "v.png").string(), 3,
         "); did you mean 'shadow.V'?"},
    };
    for (const Row &row : rows) {
        INFO("aaf " << row.args);
        fs::remove(output);
        const aaf_test::RunResult result = run_aaf(row.args);
        INFO(result.output);
        CHECK(result.exit_code == row.exit_code);
        if (row.exit_code != 0) CHECK_FALSE(fs::exists(output));  // refused before anything ran
        const std::vector<std::string> lines = lines_of(result.output);
        if (row.line.empty()) {
            CHECK(lines.empty());
            continue;
        }
        if (row.exit_code != 0) REQUIRE(lines.size() == 1);  // the error alone
        const std::string prefix = row.exit_code == 0 ? "aaf: warning: " : "aaf: error: ";
        const auto named = std::find_if(lines.begin(), lines.end(), [&](const std::string &line) {
            return line.rfind(prefix, 0) == 0 && line.find(row.line) != std::string::npos;
        });
        CHECK(named != lines.end());
    }
}

TEST_CASE("CLI filter: a Blender object-index pass left at 0 gives way to the tracer's ids beside it",
          "[cli][messages][synonyms]") {
    const fs::path dir = scratch_dir("messages_ids");
    const aaf::AovSet render = small_render();
    const std::string contract = (dir / "contract.exr").string(),
                      completed = (dir / "completed.exr").string();
    aaf::io::write_aovs(render, contract);
    aaf::io::write_aovs(blender_file(render, /*tracer_ids=*/true), completed);

    const aaf_test::RunResult result =
        run_aaf("filter aaf " + completed + " -o " + (dir / "completed_aaf.exr").string());
    REQUIRE(result.exit_code == 0);
    CHECK_THAT(result.output, Catch::Contains("aaf: note: " + completed +
                                              ": object id channel 'ViewLayer.IndexOB.X' is 0 everywhere; "
                                              "reading the object ids from 'ViewLayer.id.object' instead"));
    CHECK_THAT(result.output, !Catch::Contains("warning"));
    REQUIRE(run_aaf("filter aaf " + contract + " -o " + (dir / "contract_aaf.exr").string()).exit_code == 0);
    // The filter ran as on the tracer's own file: the same ids, the same pixels.
    const aaf::AovSet a = aaf::io::read_aovs((dir / "completed_aaf.exr").string());
    const aaf::AovSet b = aaf::io::read_aovs((dir / "contract_aaf.exr").string());
    bool filtered = false;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            CHECK(a.channel("ViewLayer.aaf.V")(x, y) == b.channel("aaf.V")(x, y));
            CHECK(a.channel("ViewLayer.aaf_beta.X")(x, y) == b.channel("aaf_beta.X")(x, y));
            filtered = filtered || b.channel("aaf_beta.X")(x, y) > 0;
        }
    CHECK(filtered);
}
