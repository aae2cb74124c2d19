#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "aaf/core/util/error.h"
#include "aaf/io/exr_io.h"
#include "aaf/io/preview.h"

#include "../scratch_dir.h"

using namespace aaf;
using aaf_test::scratch_dir;
namespace fs = std::filesystem;

namespace {

std::size_t file_count(const fs::path &dir) {
    return std::size_t(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

}  // namespace

TEST_CASE("EXR round-trip keeps every channel bit-exact and the attributes", "[io]") {
    const fs::path dir = scratch_dir("roundtrip");
    AovSet aovs(5, 3);
    PlaneView a = aovs.add_channel("shadow.V");
    PlaneView b = aovs.add_channel("P.X");
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 5; ++x) {
            a(x, y) = 0.1f * x + 0.01f * y;
            b(x, y) = -1e-7f * (x + 1) * (y + 3);
        }
    aovs.add_channel("R", 0.25f);
    aovs.attributes["aaf:light:center"] = Vec3{1.5f, -2.0f, 3.25f};
    aovs.attributes["aaf:light:sigma_m"] = 0.5f;
    aovs.attributes["aaf:seed"] = 42;
    aovs.attributes["aaf:light:kind"] = std::string("gaussian");

    const std::string path = (dir / "aovs.exr").string();
    io::write_aovs(aovs, path);
    CHECK(file_count(dir) == 1);  // no temporary left behind
    const AovSet back = io::read_aovs(path);
    REQUIRE(back.width() == 5);
    REQUIRE(back.height() == 3);
    for (const std::string &name : aovs.channel_names()) {
        REQUIRE(back.has_channel(name));
        for (int y = 0; y < 3; ++y)
            for (int x = 0; x < 5; ++x) CHECK(back.channel(name)(x, y) == aovs.channel(name)(x, y));
    }
    const Vec3 centre = std::get<Vec3>(back.attributes.at("aaf:light:center"));
    CHECK(centre.x == 1.5f);
    CHECK(centre.z == 3.25f);
    CHECK(std::get<float>(back.attributes.at("aaf:light:sigma_m")) == 0.5f);
    CHECK(std::get<int>(back.attributes.at("aaf:seed")) == 42);
    CHECK(std::get<std::string>(back.attributes.at("aaf:light:kind")) == "gaussian");
}

TEST_CASE("read_aov_header gives read_aovs' channels, storage and attributes without the pixels", "[io]") {
    const fs::path dir = scratch_dir("header_only");
    AovSet aovs(40, 30);
    aovs.add_channel("shadow.V", 0.5f);
    aovs.add_channel("R", 0.25f);
    aovs.set_precision("R", Precision::Half);
    aovs.attributes["aaf:light:sigma_m"] = 0.5f;
    aovs.attributes["aaf:light:kind"] = std::string("gaussian");
    const std::string path = (dir / "aovs.exr").string();
    io::write_aovs(aovs, path);

    const AovSet full = io::read_aovs(path);
    io::ImageLayout layout;
    const AovSet header = io::read_aov_header(path, layout);
    CHECK(header.channel_names() == full.channel_names());
    for (std::size_t c = 0; c < full.channel_names().size(); ++c)
        CHECK(header.precision(c) == full.precision(c));
    CHECK(header.attributes.size() == full.attributes.size());
    CHECK(std::get<float>(header.attributes.at("aaf:light:sigma_m")) == 0.5f);
    CHECK(header.pixel_count() == 1);  // a stand-in: the size is the layout's
    CHECK(layout.data_window().width == 40);
    CHECK(layout.data_window().height == 30);
    CHECK(layout.format_name() == "openexr");

    // Damaged pixels (the last chunk's compressed bytes): the header still reads, the pixels do not.
    {
        const auto size = fs::file_size(path);
        std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
        file.seekp(std::streamoff(size - 32));
        for (int i = 0; i < 32; ++i) file.put(char(0x5a));
    }
    io::ImageLayout again;
    CHECK(io::read_aov_header(path, again).channel_names() == full.channel_names());
    CHECK_THROWS_AS(io::read_aovs(path), InputError);
    CHECK_THROWS_WITH(io::read_aov_header((dir / "missing.exr").string(), again),
                      Catch::Contains("missing.exr"));
}

TEST_CASE("Unreadable inputs give an error naming the file", "[io]") {
    const fs::path dir = scratch_dir("bad_input");
    CHECK_THROWS_WITH(io::read_aovs((dir / "missing.exr").string()), Catch::Contains("missing.exr"));
    CHECK_THROWS_AS(io::read_aovs((dir / "missing.exr").string()), InputError);
    const fs::path garbage = dir / "garbage.exr";
    std::ofstream(garbage) << "not an image";
    CHECK_THROWS_WITH(io::read_aovs(garbage.string()), Catch::Contains("garbage.exr"));
}

TEST_CASE("A failed write leaves nothing behind and names the file", "[io]") {
    const fs::path dir = scratch_dir("bad_output");
    AovSet aovs(2, 2);
    aovs.add_channel("R");
    const std::string path = (dir / "no_such_dir" / "out.exr").string();
    CHECK_THROWS_WITH(io::write_aovs(aovs, path), Catch::Contains("out.exr"));
    CHECK(file_count(dir) == 0);
}

TEST_CASE("Rewriting an existing file replaces it whole", "[io]") {
    const fs::path dir = scratch_dir("replace");
    const std::string path = (dir / "img.exr").string();
    AovSet first(4, 4), second(2, 2);
    first.add_channel("R", 1.0f);
    second.add_channel("G", 2.0f);
    io::write_aovs(first, path);
    io::write_aovs(second, path);
    const AovSet back = io::read_aovs(path);
    CHECK(back.width() == 2);
    CHECK(!back.has_channel("R"));
    CHECK(back.channel("G")(1, 1) == 2.0f);
    CHECK(file_count(dir) == 1);
}

TEST_CASE("PNG preview encodes colour with the sRGB curve and writes data as it is", "[io][preview]") {
    const fs::path dir = scratch_dir("preview");
    AovSet aovs(3, 1);
    PlaneView grey = aovs.add_channel("Y");
    grey(0, 0) = 0.0f;
    grey(1, 0) = 0.2140f;  // sRGB encodes 0.214 as ~0.5 (127.5 / 255)
    grey(2, 0) = 4.0f;     // clipped to white
    const std::string path = (dir / "v.png").string();
    CHECK(io::write_preview_png(aovs, {"Y"}, path) == "embedded aaf-default");
    const AovSet back = io::read_aovs(path);
    REQUIRE(back.has_channel("R"));
    CHECK(back.channel("R")(0, 0) == 0.0f);
    CHECK(back.channel("G")(1, 0) == Approx(0.5f).margin(1.5f / 255));
    CHECK(back.channel("B")(2, 0) == 1.0f);
    CHECK_THROWS_WITH(io::write_preview_png(aovs, {"nope"}, path), Catch::Contains("nope"));

    // A data channel (visibility) is never colour converted: 0.214 stays 0.214.
    PlaneView visibility = aovs.add_channel("shadow.V");
    visibility(1, 0) = 0.2140f;
    CHECK(io::write_preview_png(aovs, {"shadow.V"}, path).empty());
    CHECK(io::read_aovs(path).channel("G")(1, 0) == Approx(0.214f).margin(1.0f / 255));

    // Nor are the .Y (or Arnold's .R) components of positions and normals.
    for (const char *name : {"P.G", "P.B"}) aovs.add_channel(name);
    for (const char *name : {"P.Y", "N.Y", "motion.Y", "P.R"}) {
        aovs.add_channel(name)(1, 0) = 0.2140f;
        CHECK(io::write_preview_png(aovs, {name}, path).empty());
        CHECK(io::read_aovs(path).channel("G")(1, 0) == Approx(0.214f).margin(1.0f / 255));
    }
}

namespace {

/// An OCIO config whose only view encodes linear values with x^(1/power).
std::string write_power_config(const fs::path &path, int power) {
    std::ofstream(path) << "ocio_profile_version: 2\n"
                           "roles: {default: lin, scene_linear: lin}\n"
                           "displays:\n  Test:\n    - !<View> {name: Root, colorspace: root}\n"
                           "colorspaces:\n  - !<ColorSpace> {name: lin}\n"
                           "  - !<ColorSpace>\n    name: root\n"
                           "    from_reference: !<ExponentTransform> {value: ["
                        << power << ", " << power << ", " << power << ", 1], direction: inverse}\n";
    return path.string();
}

}  // namespace

TEST_CASE("PNG preview uses --ocio-config, then $OCIO, then the embedded config", "[io][preview][ocio]") {
    const fs::path dir = scratch_dir("preview_ocio");
    AovSet aovs(1, 1);
    aovs.add_channel("R")(0, 0) = 0.25f;
    aovs.add_channel("G")(0, 0) = 0.25f;
    aovs.add_channel("B")(0, 0) = 0.25f;
    const std::string square_root = write_power_config(dir / "root2.ocio", 2);
    const std::string fourth_root = write_power_config(dir / "root4.ocio", 4);
    const std::string path = (dir / "p.png").string();
    auto shown = [&] { return io::read_aovs(path).channel("R")(0, 0); };

    ::setenv("OCIO", square_root.c_str(), 1);
    CHECK(io::write_preview_png(aovs, {"R", "G", "B"}, path) == square_root);
    CHECK(shown() == Approx(0.5f).margin(1.0f / 255));  // sqrt(0.25)
    io::PreviewOptions options;
    options.ocio_config = fourth_root;  // the option beats $OCIO
    CHECK(io::write_preview_png(aovs, {"R", "G", "B"}, path, options) == fourth_root);
    CHECK(shown() == Approx(0.7071f).margin(1.0f / 255));
    ::unsetenv("OCIO");
    io::write_preview_png(aovs, {"R", "G", "B"}, path);
    CHECK(shown() == Approx(0.5371f).margin(1.0f / 255));  // sRGB-encoded 0.25
    options.ocio_config = (dir / "missing.ocio").string();
    // The file at fault is named: the config, not the picture.
    CHECK_THROWS_AS(io::write_preview_png(aovs, {"R", "G", "B"}, path, options), InputError);
    CHECK_THROWS_WITH(io::write_preview_png(aovs, {"R", "G", "B"}, path, options),
                      Catch::Contains("missing.ocio: cannot read the OpenColorIO config"));
}

TEST_CASE("PNG preview shows the display window, the data window in place", "[io][preview]") {
    const fs::path dir = scratch_dir("preview_window");
    AovSet aovs(2, 2);
    for (const char *c : {"R", "G", "B"}) {
        PlaneView plane = aovs.add_channel(c);
        for (int y = 0; y < 2; ++y)
            for (int x = 0; x < 2; ++x) plane(x, y) = 1.0f;
    }
    io::PreviewOptions options;
    options.data_window = {3, 1, 2, 2};     // pixels at x 3-4, y 1-2...
    options.display_window = {0, 0, 4, 3};  // ...of a 4x3 picture: x 4 is cropped
    const std::string path = (dir / "w.png").string();
    io::write_preview_png(aovs, {"R", "G", "B"}, path, options);
    const AovSet back = io::read_aovs(path);
    REQUIRE(back.width() == 4);
    REQUIRE(back.height() == 3);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x) CHECK(back.channel("G")(x, y) == ((x == 3 && y >= 1) ? 1.0f : 0.0f));
}

TEST_CASE("Half channels are written as half, read back as half, the rest stays float", "[io][half]") {
    const fs::path dir = scratch_dir("half");
    AovSet aovs(4, 2);
    PlaneView colour = aovs.add_channel("albedo.R");
    PlaneView data = aovs.add_channel("P.X");
    for (int x = 0; x < 4; ++x) {
        colour(x, 0) = 0.1f * float(x) + 1e-4f;   // not representable in half
        data(x, 0) = 1000.0f + 1e-3f * float(x);  // needs float: half steps by 0.5 here
    }
    aovs.set_precision("albedo.R", Precision::Half);
    const std::string path = (dir / "half.exr").string();
    io::write_aovs(aovs, path);
    const AovSet back = io::read_aovs(path);
    // EXR stores channels sorted by name: look them up.
    auto precision_of = [](const AovSet &set, const std::string &name) {
        const auto &names = set.channel_names();
        return set.precision(std::size_t(std::find(names.begin(), names.end(), name) - names.begin()));
    };
    CHECK(precision_of(back, "albedo.R") == Precision::Half);
    CHECK(precision_of(back, "P.X") == Precision::Float);
    for (int x = 0; x < 4; ++x) {
        CHECK(back.channel("albedo.R")(x, 0) == Approx(colour(x, 0)).epsilon(1e-3));  // half: 11 bits
        CHECK(back.channel("P.X")(x, 0) == data(x, 0));                               // float: exact
    }
    CHECK(back.channel("albedo.R")(1, 0) != colour(1, 0));
    // Writing what was read keeps the types: a pass-through does not widen or narrow.
    io::write_aovs(back, (dir / "again.exr").string());
    CHECK(precision_of(io::read_aovs((dir / "again.exr").string()), "albedo.R") == Precision::Half);
}
