// `aaf filter` as a compositing step: nothing of the input is lost, the
// output's form is selectable, other renderers' names are found, bad input
// is refused with its exit code and no output.
#include <catch2/catch.hpp>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <vector>

#include "aaf/io/exr_io.h"
#include "aaf/trace/render.h"
#include "run_aaf.h"

namespace fs = std::filesystem;
using aaf_test::run_aaf;
using aaf_test::scratch_dir;
using OIIO::TypeDesc;

namespace {

constexpr int kWidth = 32, kHeight = 24;

aaf::AovSet small_render() {
    aaf::trace::RenderSettings settings;
    settings.width = kWidth;
    settings.height = kHeight;
    settings.spp = 4;
    return aaf::trace::render_scene("grids", settings);
}

/// Writes a two-part EXR as a renderer might: part 0 holds the AAF AOVs, an
/// unknown layer, custom attributes of several types and a data window offset
/// inside a larger display window; part 1 ("extra") a half layer of its own.
void write_two_part_input(const fs::path &path, const aaf::AovSet &aovs) {
    OIIO::ImageSpec first(kWidth, kHeight, int(aovs.channel_names().size()) + 1, TypeDesc::FLOAT);
    first.channelnames = aovs.channel_names();
    first.channelnames.push_back("custom.mask");
    first.x = 10;
    first.y = 5;
    first.full_x = first.full_y = 0;
    first.full_width = 64;
    first.full_height = 48;
    first.attribute("compression", "zip");
    first.attribute("name", "rgba");  // EXR multi-part files name their parts
    first.attribute("studio:shot", "sq010_sh020");
    const float world_to_camera[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1.5f, -2, 3, 1};
    first.attribute("worldToCamera", OIIO::TypeMatrix44, world_to_camera);
    const int frame_range[2] = {1001, 1100};
    first.attribute("studio:range", TypeDesc(TypeDesc::INT, 2), frame_range);
    for (const auto &[name, value] : aovs.attributes) {
        if (const aaf::Vec3 *v = std::get_if<aaf::Vec3>(&value)) {
            const float data[3] = {v->x, v->y, v->z};
            first.attribute(name, OIIO::TypeVector, data);
        } else if (const float *f = std::get_if<float>(&value)) {
            first.attribute(name, *f);
        } else if (const int *i = std::get_if<int>(&value)) {
            first.attribute(name, *i);
        } else if (const std::string *s = std::get_if<std::string>(&value)) {
            first.attribute(name, *s);
        }
    }
    std::vector<float> pixels;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            for (std::size_t c = 0; c < aovs.channel_names().size(); ++c)
                pixels.push_back(aovs.plane(c)[std::size_t(y) * kWidth + x]);
            pixels.push_back(float(x % 2));  // custom.mask
        }
    OIIO::ImageSpec second(8, 4, 2, TypeDesc::HALF);
    second.channelnames = {"extra.u", "extra.v"};
    second.attribute("name", "extra");
    second.full_width = 64;  // parts of one file share the display window
    second.full_height = 48;
    second.attribute("compression", "piz");
    std::vector<float> extra;
    for (int i = 0; i < 8 * 4; ++i) extra.insert(extra.end(), {0.25f * float(i), -float(i)});

    const OIIO::ImageSpec specs[2] = {first, second};
    auto out = OIIO::ImageOutput::create("openexr");
    const bool opened = out->open(path.string(), 2, specs);
    INFO(out->geterror());
    REQUIRE(opened);
    REQUIRE(out->write_image(TypeDesc::FLOAT, pixels.data()));
    REQUIRE(out->open(path.string(), second, OIIO::ImageOutput::AppendSubimage));
    REQUIRE(out->write_image(TypeDesc::FLOAT, extra.data()));
    REQUIRE(out->close());
}

std::vector<float> read_part(const fs::path &path, int part, const std::string &channel) {
    auto in = OIIO::ImageInput::open(path.string());
    REQUIRE(in);
    const OIIO::ImageSpec spec = in->spec(part, 0);
    const int c = spec.channelindex(channel);
    REQUIRE(c >= 0);
    std::vector<float> values(std::size_t(spec.width) * spec.height);
    REQUIRE(in->read_image(part, 0, c, c + 1, TypeDesc::FLOAT, values.data()));
    return values;
}

}  // namespace

TEST_CASE("CLI filter: custom attributes, an unknown layer, windows and a second EXR part survive",
          "[cli][pipeline]") {
    const fs::path dir = scratch_dir("pipeline_survive");
    write_two_part_input(dir / "in.exr", small_render());
    const auto result =
        run_aaf("filter aaf " + (dir / "in.exr").string() + " -o " + (dir / "out.exr").string());
    REQUIRE(result.exit_code == 0);

    auto in = OIIO::ImageInput::open((dir / "out.exr").string());
    REQUIRE(in);
    const OIIO::ImageSpec first = in->spec(0, 0);
    CHECK(first.x == 10);
    CHECK(first.y == 5);
    CHECK(first.full_width == 64);
    CHECK(first.full_height == 48);
    CHECK(first.get_string_attribute("studio:shot") == "sq010_sh020");
    const OIIO::ParamValue *matrix = first.find_attribute("worldToCamera", OIIO::TypeMatrix44);
    REQUIRE(matrix);
    CHECK(static_cast<const float *>(matrix->data())[12] == 1.5f);
    const OIIO::ParamValue *range = first.find_attribute("studio:range");
    REQUIRE(range);
    // EXR stores int[2] as a v2i; the output keeps exactly the input's type.
    auto source = OIIO::ImageInput::open((dir / "in.exr").string());
    CHECK(range->type() == source->spec().find_attribute("studio:range")->type());
    CHECK(static_cast<const int *>(range->data())[1] == 1100);
    CHECK(first.channelindex("aaf.V") >= 0);
    CHECK(read_part(dir / "out.exr", 0, "custom.mask") == read_part(dir / "in.exr", 0, "custom.mask"));

    const OIIO::ImageSpec second = in->spec(1, 0);
    CHECK(second.width == 8);
    CHECK(second.get_string_attribute("name") == "extra");
    CHECK(second.channelformat(0) == TypeDesc::HALF);
    CHECK(read_part(dir / "out.exr", 1, "extra.v") == read_part(dir / "in.exr", 1, "extra.v"));
    CHECK(read_part(dir / "out.exr", 1, "extra.u")[5] == 1.25f);
}

TEST_CASE("CLI filter: --keep-beauty, --half and --compression choose the output's form", "[cli][pipeline]") {
    const fs::path dir = scratch_dir("pipeline_form");
    const std::string input = (dir / "in.exr").string();
    aaf::io::write_aovs(small_render(), input);
    const aaf::AovSet original = aaf::io::read_aovs(input);

    REQUIRE(
        run_aaf("filter aaf " + input + " -o " + (dir / "kept.exr").string() + " --keep-beauty").exit_code ==
        0);
    const aaf::AovSet kept = aaf::io::read_aovs((dir / "kept.exr").string());
    const aaf::AovSet replaced = [&] {
        REQUIRE(run_aaf("filter aaf " + input + " -o " + (dir / "replaced.exr").string()).exit_code == 0);
        return aaf::io::read_aovs((dir / "replaced.exr").string());
    }();
    for (const char *c : {"R", "G", "B"}) {
        const std::string name = c;
        auto plane = [](const aaf::AovSet &set, const std::string &n) {
            const auto view = set.channel(n);
            return std::vector<float>(view.data, view.data + set.pixel_count());
        };
        CHECK(plane(kept, name) == plane(original, name));           // untouched
        CHECK(plane(kept, "aaf." + name) == plane(replaced, name));  // the filtered image beside it
        CHECK(plane(replaced, "noisy." + name) == plane(original, name));
        CHECK_FALSE(kept.has_channel("noisy." + name));
    }

    REQUIRE(
        run_aaf("filter aaf " + input + " -o " + (dir / "half.exr").string() + " --half --compression piz")
            .exit_code == 0);
    auto half = OIIO::ImageInput::open((dir / "half.exr").string());
    REQUIRE(half);
    const OIIO::ImageSpec &spec = half->spec();
    CHECK(spec.get_string_attribute("compression") == "piz");
    CHECK(spec.channelformat(spec.channelindex("R")) == TypeDesc::HALF);
    CHECK(spec.channelformat(spec.channelindex("unshadowed.G")) == TypeDesc::HALF);
    CHECK(spec.channelformat(spec.channelindex("P.X")) == TypeDesc::FLOAT);
    CHECK(spec.channelformat(spec.channelindex("aaf.V")) == TypeDesc::FLOAT);

    // DWAA is lossy: it compresses the colour part; the data goes to a ZIP
    // part of its own and reads back bit for bit.
    REQUIRE(run_aaf("filter aaf " + input + " -o " + (dir / "dwaa.exr").string() + " --compression dwaa")
                .exit_code == 0);
    auto dwaa = OIIO::ImageInput::open((dir / "dwaa.exr").string());
    REQUIRE(dwaa);
    const OIIO::ImageSpec colour_part = dwaa->spec(0, 0), data_part = dwaa->spec(1, 0);
    CHECK(std::string(colour_part.get_string_attribute("compression")).rfind("dwaa", 0) == 0);
    CHECK(colour_part.channelindex("R") >= 0);
    CHECK(colour_part.channelindex("unshadowed.G") >= 0);
    CHECK(colour_part.channelindex("P.Y") < 0);
    CHECK(data_part.get_string_attribute("compression") == "zip");
    // aaf info lists the data part and, like aaf filter, reads the AOVs from it.
    const auto info = run_aaf("info " + (dir / "dwaa.exr").string());
    CHECK_THAT(info.output, Catch::Contains("part 1 'data'") && Catch::Contains("aaf      ready"));
    CHECK(data_part.get_string_attribute("name") == aaf::io::kDataPartName);
    const int visibility = data_part.channelindex("aaf.V"), position_y = data_part.channelindex("P.Y");
    REQUIRE(visibility >= 0);
    REQUIRE(position_y >= 0);
    std::vector<float> data(std::size_t(kWidth) * kHeight * data_part.nchannels);
    REQUIRE(dwaa->read_image(1, 0, 0, data_part.nchannels, TypeDesc::FLOAT, data.data()));
    const auto position = original.channel("P.Y");
    const aaf::AovSet reference = aaf::io::read_aovs((dir / "replaced.exr").string());
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const std::size_t pixel = std::size_t(y) * kWidth + x;
            CHECK(data[pixel * data_part.nchannels + position_y] == position(x, y));
            CHECK(data[pixel * data_part.nchannels + visibility] == reference.channel("aaf.V")(x, y));
        }
}

TEST_CASE("CLI filter: --half keeps Arnold's data layers P.R and N.R float", "[cli][pipeline][synonyms]") {
    const fs::path dir = scratch_dir("pipeline_arnold_half");
    const aaf::AovSet render = small_render();
    aaf::AovSet arnold(kWidth, kHeight);
    arnold.attributes = render.attributes;
    auto rename = [](const std::string &name) -> std::string {
        const char *rgb[] = {"R", "G", "B"};
        for (int axis = 0; axis < 3; ++axis) {
            if (name == std::string("P.") + "XYZ"[axis]) return std::string("P.") + rgb[axis];
            if (name == std::string("N.") + "XYZ"[axis]) return std::string("N.") + rgb[axis];
            if (name == rgb[axis]) return std::string("RGBA.") + rgb[axis];
        }
        return name;
    };
    for (std::size_t c = 0; c < render.channel_names().size(); ++c) {
        aaf::PlaneView plane = arnold.add_channel(rename(render.channel_names()[c]));
        std::copy(render.plane(c).begin(), render.plane(c).end(), plane.data);
    }
    const std::string input = (dir / "arnold.exr").string(), output = (dir / "out.exr").string();
    aaf::io::write_aovs(arnold, input);
    REQUIRE(run_aaf("filter aaf " + input + " -o " + output + " --half").exit_code == 0);
    auto file = OIIO::ImageInput::open(output);
    REQUIRE(file);
    const OIIO::ImageSpec &spec = file->spec();
    CHECK(spec.channelformat(spec.channelindex("RGBA.R")) == TypeDesc::HALF);
    CHECK(spec.channelformat(spec.channelindex("P.R")) == TypeDesc::FLOAT);
    CHECK(spec.channelformat(spec.channelindex("N.G")) == TypeDesc::FLOAT);
}

TEST_CASE("CLI filter: Blender view-layer names are found without --map", "[cli][pipeline][synonyms]") {
    const fs::path dir = scratch_dir("pipeline_blender");
    const aaf::AovSet render = small_render();
    // As Blender names passes in a multilayer EXR: "<view layer>.<pass>.<channel>", with spaces.
    aaf::AovSet blender(kWidth, kHeight);
    blender.attributes = render.attributes;
    auto rename = [](const std::string &name) -> std::string {
        const std::string layer = "View Layer.";
        if (name == "R" || name == "G" || name == "B") return layer + "Combined." + name;
        if (name.rfind("P.", 0) == 0) return layer + "Position." + name.substr(2);
        if (name.rfind("N.", 0) == 0) return layer + "Normal." + name.substr(2);
        if (name == "id.object") return layer + "IndexOB.X";
        return layer + name;  // custom AOVs under the contract's names
    };
    for (std::size_t c = 0; c < render.channel_names().size(); ++c) {
        aaf::PlaneView plane = blender.add_channel(rename(render.channel_names()[c]));
        std::copy(render.plane(c).begin(), render.plane(c).end(), plane.data);
    }
    aaf::io::write_aovs(blender, (dir / "blender.exr").string());
    aaf::io::write_aovs(render, (dir / "contract.exr").string());

    REQUIRE(
        run_aaf("filter aaf " + (dir / "blender.exr").string() + " -o " + (dir / "blender_aaf.exr").string())
            .exit_code == 0);
    REQUIRE(run_aaf("filter aaf " + (dir / "contract.exr").string() + " -o " +
                    (dir / "contract_aaf.exr").string())
                .exit_code == 0);
    const aaf::AovSet a = aaf::io::read_aovs((dir / "blender_aaf.exr").string());
    const aaf::AovSet b = aaf::io::read_aovs((dir / "contract_aaf.exr").string());
    // The same filter ran: the filtered beauty lands in Blender's Combined
    // pass, the other outputs under the same view layer (Blender hides
    // layers without it), none outside it.
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            CHECK(a.channel("View Layer.Combined.G")(x, y) == b.channel("G")(x, y));
            CHECK(a.channel("View Layer.aaf.V")(x, y) == b.channel("aaf.V")(x, y));
            CHECK(a.channel("View Layer.aaf_beta.X")(x, y) == b.channel("aaf_beta.X")(x, y));
            CHECK(a.channel("View Layer.noisy.G")(x, y) == b.channel("noisy.G")(x, y));
        }
    for (const std::string &name : a.channel_names()) CHECK(name.rfind("View Layer.", 0) == 0);
}

TEST_CASE("CLI filter: NaN and Inf inputs are replaced and counted, never spread", "[cli][pipeline]") {
    const fs::path dir = scratch_dir("pipeline_nan");
    aaf::AovSet aovs = small_render();
    aovs.channel("shadow.V")(16, 12) = std::numeric_limits<float>::quiet_NaN();
    aovs.channel("shadow.V")(3, 3) = std::numeric_limits<float>::infinity();
    aovs.channel("P.X")(5, 5) = -std::numeric_limits<float>::infinity();
    aaf::io::write_aovs(aovs, (dir / "in.exr").string());
    const auto result =
        run_aaf("filter aaf " + (dir / "in.exr").string() + " -o " + (dir / "out.exr").string());
    REQUIRE(result.exit_code == 0);
    CHECK_THAT(result.output, Catch::Contains("aaf: warning: ") &&
                                  Catch::Contains("in.exr: replaced 3 NaN/Inf") &&
                                  Catch::Contains("shadow.V 2") && Catch::Contains("P.X 1"));
    const aaf::AovSet out = aaf::io::read_aovs((dir / "out.exr").string());
    for (const char *name : {"aaf.V", "R", "G", "B", "aaf_beta.X"})
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) CHECK(std::isfinite(out.channel(name)(x, y)));
}

TEST_CASE("CLI filter: each bad input gives its exit code and leaves no output", "[cli][pipeline][errors]") {
    const fs::path dir = scratch_dir("pipeline_bad");
    const std::string good = (dir / "good.exr").string(), out = (dir / "out.exr").string();
    aaf::io::write_aovs(small_render(), good);

    // Truncated: the first half of a valid file.
    {
        std::ifstream in(good, std::ios::binary);
        std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        std::ofstream((dir / "truncated.exr").string(), std::ios::binary)
            << bytes.substr(0, bytes.size() / 2);
    }
    std::ofstream((dir / "text.exr").string()) << "not an image\n";
    aaf::AovSet no_d1 = small_render();
    aaf::AovSet stripped(kWidth, kHeight);
    stripped.attributes = no_d1.attributes;
    for (std::size_t c = 0; c < no_d1.channel_names().size(); ++c)
        if (no_d1.channel_names()[c] != "shadow.d1") {
            aaf::PlaneView plane = stripped.add_channel(no_d1.channel_names()[c]);
            std::copy(no_d1.plane(c).begin(), no_d1.plane(c).end(), plane.data);
        }
    aaf::io::write_aovs(stripped, (dir / "no_d1.exr").string());
    aaf::AovSet no_light = small_render();
    no_light.attributes.erase("aaf:light:sigma_m");
    aaf::io::write_aovs(no_light, (dir / "no_light.exr").string());

    const struct {
        const char *file;
        const char *message;
    } cases[] = {
        {"truncated.exr", "truncated.exr"},
        {"text.exr", "text.exr"},
        {"missing.exr", "missing.exr"},
        {"no_d1.exr", "missing 1 input of AAF: d1 [shadow.d1]: aaf render SCENE --aovs shadow"},
        {"no_light.exr", "missing 1 input of AAF: header aaf:light:sigma_m: --light LIGHT.json"},
    };
    for (const auto &c : cases) {
        INFO(c.file);
        const auto result = run_aaf("filter aaf " + (dir / c.file).string() + " -o " + out);
        CHECK(result.exit_code == 3);
        CHECK_THAT(result.output, Catch::StartsWith("aaf: error: ") && Catch::Contains(c.message));
        CHECK(std::count(result.output.begin(), result.output.end(), '\n') == 1);
        CHECK_FALSE(fs::exists(out));
    }
    CHECK(run_aaf("filter aaf " + good + " -o " + out + " --compression lzw").exit_code == 2);  // usage
    CHECK_FALSE(fs::exists(out));
    // No temporary files are left behind by any of the failures.
    for (const auto &entry : fs::directory_iterator(dir))
        CHECK(entry.path().filename().string().find(".tmp-") == std::string::npos);
}

TEST_CASE("CLI preview: the display window, --layer, and data layers shown as they are",
          "[cli][pipeline][preview]") {
    const fs::path dir = scratch_dir("pipeline_preview");
    write_two_part_input(dir / "in.exr", small_render());
    REQUIRE(run_aaf("filter aaf " + (dir / "in.exr").string() + " -o " + (dir / "out.exr").string() +
                    " --keep-beauty")
                .exit_code == 0);
    const std::string out = (dir / "out.exr").string();
    REQUIRE(run_aaf("preview " + out + " -o " + (dir / "beauty.png").string()).exit_code == 0);
    const aaf::AovSet beauty = aaf::io::read_aovs((dir / "beauty.png").string());
    CHECK(beauty.width() == 64);  // the display window, not the 32x24 data window
    CHECK(beauty.height() == 48);
    CHECK(beauty.channel("G")(0, 0) == 0.0f);  // outside the data window

    REQUIRE(run_aaf("preview " + out + " -o " + (dir / "filtered.png").string() + " --layer aaf").exit_code ==
            0);
    REQUIRE(run_aaf("preview " + out + " -o " + (dir / "position.png").string() + " --layer P").exit_code ==
            0);
    // Positions are data: P.Y of the ground (0) shows as 0, not through the sRGB curve.
    const aaf::AovSet position = aaf::io::read_aovs((dir / "position.png").string());
    const aaf::AovSet input = aaf::io::read_aovs(out);
    const float y_value = input.channel("P.Y")(0, 23);
    CHECK(position.channel("G")(10, 5 + 23) == Approx(std::clamp(y_value, 0.0f, 1.0f)).margin(1.0f / 255));

    const auto ambiguous = run_aaf("preview " + out + " -o " + (dir / "x.png").string() + " --layer shadow");
    CHECK(ambiguous.exit_code == 3);
    CHECK_THAT(ambiguous.output, Catch::Contains("layer 'shadow'") && Catch::Contains("shadow.V"));
}

namespace {

/// Writes `aovs` as a two-part EXR: the channels in `second` go to part
/// "geometry" (of size `second_width` x `second_height`, filled with the
/// first rows of the data when smaller), the rest to part "rgba".
void write_split_parts(const fs::path &path, const aaf::AovSet &aovs, const std::vector<std::string> &second,
                       int second_width, int second_height) {
    std::vector<std::string> first_names, second_names;
    for (const std::string &name : aovs.channel_names())
        (std::find(second.begin(), second.end(), name) != second.end() ? second_names : first_names)
            .push_back(name);
    auto make_spec = [&](const std::vector<std::string> &names, int width, int height, const char *part) {
        OIIO::ImageSpec spec(width, height, int(names.size()), TypeDesc::FLOAT);
        spec.channelnames = names;
        spec.attribute("name", part);
        spec.full_width = kWidth;
        spec.full_height = kHeight;
        return spec;
    };
    auto interleave = [&](const std::vector<std::string> &names, int width, int height) {
        std::vector<float> pixels;
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x)
                for (const std::string &name : names) pixels.push_back(aovs.channel(name)(x, y));
        return pixels;
    };
    OIIO::ImageSpec specs[2] = {make_spec(first_names, kWidth, kHeight, "rgba"),
                                make_spec(second_names, second_width, second_height, "geometry")};
    for (const auto &[name, value] : aovs.attributes) {
        if (const aaf::Vec3 *v = std::get_if<aaf::Vec3>(&value)) {
            const float data[3] = {v->x, v->y, v->z};
            specs[0].attribute(name, OIIO::TypeVector, data);
        } else if (const float *f = std::get_if<float>(&value)) {
            specs[0].attribute(name, *f);
        } else if (const std::string *s = std::get_if<std::string>(&value)) {
            specs[0].attribute(name, *s);
        }
    }
    auto out = OIIO::ImageOutput::create("openexr");
    REQUIRE(out->open(path.string(), 2, specs));
    REQUIRE(out->write_image(TypeDesc::FLOAT, interleave(first_names, kWidth, kHeight).data()));
    REQUIRE(out->open(path.string(), specs[1], OIIO::ImageOutput::AppendSubimage));
    REQUIRE(out->write_image(TypeDesc::FLOAT, interleave(second_names, second_width, second_height).data()));
    REQUIRE(out->close());
}

}  // namespace

TEST_CASE("CLI filter: AOVs in other parts are read, left in place, and must share the resolution",
          "[cli][pipeline][parts]") {
    const fs::path dir = scratch_dir("pipeline_parts");
    const aaf::AovSet render = small_render();
    const std::vector<std::string> geometry = {"P.X", "P.Y", "P.Z",       "N.X",
                                               "N.Y", "N.Z", "id.object", "pixel.size"};
    write_split_parts(dir / "split.exr", render, geometry, kWidth, kHeight);
    aaf::io::write_aovs(render, (dir / "whole.exr").string());
    REQUIRE(run_aaf("filter aaf " + (dir / "split.exr").string() + " -o " + (dir / "split_aaf.exr").string())
                .exit_code == 0);
    REQUIRE(run_aaf("filter aaf " + (dir / "whole.exr").string() + " -o " + (dir / "whole_aaf.exr").string())
                .exit_code == 0);
    // The same filter ran, its outputs are in the first part, the geometry stays in its own.
    CHECK(read_part(dir / "split_aaf.exr", 0, "aaf.V") == read_part(dir / "whole_aaf.exr", 0, "aaf.V"));
    auto in = OIIO::ImageInput::open((dir / "split_aaf.exr").string());
    REQUIRE(in);
    CHECK(in->spec(0, 0).channelindex("P.X") < 0);
    CHECK(in->spec(1, 0).get_string_attribute("name") == "geometry");
    CHECK(read_part(dir / "split_aaf.exr", 1, "P.X") == read_part(dir / "split.exr", 1, "P.X"));

    // A part of another size cannot feed the filter.
    write_split_parts(dir / "mismatched.exr", render, geometry, kWidth / 2, kHeight / 2);
    const auto result =
        run_aaf("filter aaf " + (dir / "mismatched.exr").string() + " -o " + (dir / "out.exr").string());
    CHECK(result.exit_code == 3);
    CHECK_THAT(result.output,
               Catch::Contains("mismatched.exr: channel '") &&
                   Catch::Contains("in part 'geometry' of 16x12, but the first part is 32x24"));
    CHECK_FALSE(fs::exists(dir / "out.exr"));
}

TEST_CASE(
    "CLI filter: a thin-lens render keeps its defocused beauty with a note, and --compose paper warns that "
    "AAF's output has no defocus",
    "[cli][pipeline]") {
    const fs::path dir = scratch_dir("pipeline_lens");
    REQUIRE(
        run_aaf("render studio --width 24 --height 18 --spp 4 -o " + (dir / "lens.exr").string()).exit_code ==
        0);
    const auto lens =
        run_aaf("filter aaf " + (dir / "lens.exr").string() + " -o " + (dir / "out.exr").string());
    CHECK(lens.exit_code == 0);
    CHECK_THAT(lens.output, Catch::Contains("lens.exr: R,G,B left as rendered"));
    CHECK(lens.output.find("warning") == std::string::npos);
    const aaf::AovSet in = aaf::io::read_aovs((dir / "lens.exr").string());
    const aaf::AovSet out = aaf::io::read_aovs((dir / "out.exr").string());
    for (const char *c : {"R", "G", "B"}) CHECK(in.plane(in.index_of(c)) == out.plane(out.index_of(c)));
    const auto paper = run_aaf("filter aaf " + (dir / "lens.exr").string() + " --compose paper -o " +
                               (dir / "paper.exr").string());
    CHECK(paper.exit_code == 0);
    CHECK_THAT(paper.output, Catch::Contains("lens.exr: rendered through a thin lens; aaf filters"));
    aaf::io::write_aovs(small_render(), (dir / "pinhole.exr").string());
    const auto pinhole =
        run_aaf("filter aaf " + (dir / "pinhole.exr").string() + " -o " + (dir / "p.exr").string());
    CHECK(pinhole.exit_code == 0);
    CHECK(pinhole.output.find("warning") == std::string::npos);
}
