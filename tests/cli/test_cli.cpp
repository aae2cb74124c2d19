#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <utility>

#include "aaf/io/exr_io.h"
#include "aaf/trace/render.h"
#include "run_aaf.h"

namespace fs = std::filesystem;
using aaf_test::run_aaf;
using aaf_test::RunResult;
using aaf_test::scratch_dir;

TEST_CASE("CLI: render, info, filter and compare chain together", "[cli]") {
    const fs::path dir = scratch_dir("cli_chain");
    const std::string noisy = (dir / "noisy.exr").string(), out = (dir / "filtered.exr").string();
    REQUIRE(run_aaf("render grids -o " + noisy + " --width 32 --height 24 --spp 4").exit_code == 0);

    const RunResult info = run_aaf("info " + noisy);
    CHECK(info.exit_code == 0);
    CHECK_THAT(info.output, Catch::Contains("aaf:light:sigma_m") && Catch::Contains("aaf      ready"));

    REQUIRE(run_aaf("filter aaf " + noisy + " -o " + out).exit_code == 0);
    const aaf::AovSet filtered = aaf::io::read_aovs(out);
    for (const char *name : {"R", "noisy.R", "aaf.V", "aaf_beta.X", "shadow.d2max", "P.X", "pixel.spp"})
        CHECK(filtered.has_channel(name));

    const std::string plan = (dir / "plan.exr").string(), exact = (dir / "exact.exr").string();
    REQUIRE(run_aaf("plan " + noisy + " -o " + plan + " --max-spp 50").exit_code == 0);
    const aaf::AovSet planned = aaf::io::read_aovs(plan);
    REQUIRE(planned.has_channel("plan.spp"));
    for (int y = 0; y < planned.height(); ++y)
        for (int x = 0; x < planned.width(); ++x) {
            CHECK(planned.channel("plan.spp")(x, y) >= 9.0f);
            CHECK(planned.channel("plan.spp")(x, y) <= 50.0f);
        }
    REQUIRE(run_aaf("filter aaf " + noisy + " -o " + exact + " --filter 2d").exit_code == 0);
    CHECK(run_aaf("filter aaf " + noisy + " -o " + exact + " --filter 3d").exit_code == 2);

    const RunResult same = run_aaf("compare " + noisy + " " + noisy + " --json");
    CHECK(same.exit_code == 0);
    CHECK_THAT(same.output, Catch::Contains("\"rmse\":0.0"));
    const RunResult differ = run_aaf("compare " + out + " " + noisy + " --channels shadow.V");
    CHECK(differ.exit_code == 0);
    CHECK_THAT(differ.output, Catch::Contains("RMSE"));
}

TEST_CASE("CLI: render --adaptive takes exactly the samples aaf plan computes from its first pass",
          "[cli][adaptive]") {
    // The tracer is one caller of the core's sampling plan (AAF Eq. 21): its
    // second pass must follow the plan of its own 9 spp first pass, which any
    // renderer gets from `aaf plan`.
    const fs::path dir = scratch_dir("cli_adaptive");
    const std::string first = (dir / "first.exr").string(), plan = (dir / "plan.exr").string(),
                      adaptive = (dir / "adaptive.exr").string();
    const std::string view = " --width 64 --height 48 --seed 5";
    REQUIRE(run_aaf("render grids -o " + first + view + " --spp 9").exit_code == 0);
    REQUIRE(run_aaf("plan " + first + " -o " + plan + " --mu 2 --max-spp 60").exit_code == 0);
    const RunResult rendered =
        run_aaf("render grids -o " + adaptive + view + " --adaptive --mu 2 --max-spp 60");
    REQUIRE(rendered.exit_code == 0);
    CHECK_THAT(rendered.output, Catch::Contains("average") || Catch::Contains("avg"));

    const aaf::AovSet planned = aaf::io::read_aovs(plan), taken = aaf::io::read_aovs(adaptive);
    int above_first_pass = 0;
    for (int y = 0; y < taken.height(); ++y)
        for (int x = 0; x < taken.width(); ++x) {
            if (taken.channel("id.object")(x, y) == 0) continue;  // background: no shadow rays
            CHECK(taken.channel("pixel.spp")(x, y) == planned.channel("plan.spp")(x, y));
            above_first_pass += taken.channel("pixel.spp")(x, y) > 9;
        }
    CHECK(above_first_pass > 100);

    // Fig. 7's debug pictures: n (and beta) as false-colour PNGs.
    const std::string picture = (dir / "n.png").string();
    REQUIRE(run_aaf("preview " + adaptive + " -o " + picture + " --channels pixel.spp --false-colour")
                .exit_code == 0);
    const aaf::AovSet png = aaf::io::read_aovs(picture);
    REQUIRE(png.width() == taken.width());
    // The fewest samples are dark blue, the most red, background black.
    int blue = 0, red = 0;
    for (int y = 0; y < png.height(); ++y)
        for (int x = 0; x < png.width(); ++x) {
            const float n = taken.channel("pixel.spp")(x, y), r = png.channel("R")(x, y),
                        b = png.channel("B")(x, y);
            if (taken.channel("id.object")(x, y) == 0) CHECK(r + b + png.channel("G")(x, y) == 0);
            if (n == 9) blue += b > r;
            if (n == 60) red += r > b;
        }
    CHECK(blue > 0);
    CHECK(red > 0);
}

TEST_CASE("CLI: bad input is one clear line, exit 3, no output written", "[cli]") {
    const fs::path dir = scratch_dir("cli_errors");
    const std::string missing = (dir / "missing.exr").string(), out = (dir / "out.exr").string();

    RunResult r = run_aaf("filter aaf " + missing + " -o " + out);
    CHECK(r.exit_code == 3);
    CHECK_THAT(r.output, Catch::StartsWith("aaf: error: ") && Catch::Contains("missing.exr"));
    CHECK(!fs::exists(out));

    // An EXR with some of the AAF AOVs: the missing role and the file are named.
    const std::string partial = (dir / "partial.exr").string();
    aaf::AovSet aovs(4, 4);
    aovs.add_channel("R");
    aovs.add_channel("shadow.d1");
    aaf::io::write_aovs(aovs, partial);
    r = run_aaf("filter aaf " + partial + " -o " + out);
    CHECK(r.exit_code == 3);
    CHECK_THAT(r.output, Catch::Contains("partial.exr") && Catch::Contains("shadow.V"));
    CHECK(!fs::exists(out));

    // One with none of them, a beauty alone.
    const std::string plain = (dir / "plain.exr").string();
    aaf::AovSet beauty(4, 4);
    beauty.add_channel("R");
    aaf::io::write_aovs(beauty, plain);

    r = run_aaf("plan " + plain + " -o " + out);
    CHECK(r.exit_code == 3);
    CHECK_THAT(r.output, Catch::Contains("plain.exr") && Catch::Contains("shadow.d1"));
    CHECK(!fs::exists(out));

    // Mismatched sizes in compare.
    const std::string small = (dir / "small.exr").string();
    aaf::AovSet tiny(2, 2);
    tiny.add_channel("R");
    aaf::io::write_aovs(tiny, small);
    r = run_aaf("compare " + small + " " + plain + " --channels R");
    CHECK(r.exit_code == 3);
    CHECK_THAT(r.output, Catch::Contains("sizes differ"));

    // The input is never overwritten.
    r = run_aaf("filter aaf " + plain + " -o " + plain);
    CHECK(r.exit_code == 3);
    CHECK(aaf::io::read_aovs(plain).has_channel("R"));
}

TEST_CASE("CLI: --map finds AOVs a renderer named differently", "[cli]") {
    const fs::path dir = scratch_dir("cli_map");
    aaf::trace::RenderSettings settings;
    settings.width = 24;
    settings.height = 18;
    const aaf::AovSet original = aaf::trace::render_scene("grids", settings);
    aaf::AovSet renamed(original.width(), original.height());
    renamed.attributes = original.attributes;
    for (std::size_t c = 0; c < original.channel_names().size(); ++c) {
        std::string name = original.channel_names()[c];
        if (name.rfind("P.", 0) == 0) name = "Pworld" + name.substr(1);  // P.X -> Pworld.X
        if (name == "shadow.V") name = "vis";
        const aaf::PlaneView plane = renamed.add_channel(name);
        std::copy(original.plane(c).begin(), original.plane(c).end(), plane.data);
    }
    const std::string in = (dir / "renamed.exr").string(), out = (dir / "out.exr").string();
    aaf::io::write_aovs(renamed, in);
    CHECK(run_aaf("filter aaf " + in + " -o " + out).exit_code == 3);  // defaults not found
    REQUIRE(run_aaf("filter aaf " + in + " -o " + out + " --map position=Pworld --map visibility=vis")
                .exit_code == 0);
    CHECK(aaf::io::read_aovs(out).has_channel("aaf.V"));
}

TEST_CASE("CLI: usage errors exit 2", "[cli]") {
    CHECK(run_aaf("filter aaf").exit_code == 2);
    CHECK(run_aaf("render grids --spp notanumber -o x.exr").exit_code == 2);
    CHECK(run_aaf("frobnicate").exit_code == 2);
    CHECK(run_aaf("--help").exit_code == 0);
}

TEST_CASE("CLI: filter aaf and filter maaf take a combined-effects render as maaf6 does, with a note",
          "[cli]") {
    const fs::path dir = scratch_dir("cli_combined");
    const std::string render = (dir / "combined.exr").string();
    REQUIRE(run_aaf("render room --aovs maaf6 --width 24 --height 18 --spp 4 -o " + render).exit_code == 0);
    // `aaf info` says so too.
    CHECK_THAT(run_aaf("info " + render).output,
               Catch::Contains("\n  aaf      ready: a combined-effects render") &&
                   Catch::Contains("\n  maaf     ready: a combined-effects render"));
    for (const auto &[asked, delegate] : {std::pair<std::string, std::string>{"aaf", "maaf6 --pairs 1"},
                                          std::pair<std::string, std::string>{"maaf", "maaf6"}}) {
        INFO(asked);
        const std::string out = (dir / (asked + ".exr")).string(), direct = (dir / "direct.exr").string();
        const RunResult run = run_aaf("filter " + asked + " " + render + " -o " + out);
        REQUIRE(run.exit_code == 0);
        CHECK_THAT(run.output, Catch::Contains("aaf: note: " + render) &&
                                   Catch::Contains("`aaf filter " + delegate + "`"));
        REQUIRE(run_aaf("filter " + delegate + " " + render + " -o " + direct).exit_code == 0);
        const aaf::AovSet a = aaf::io::read_aovs(out), b = aaf::io::read_aovs(direct);
        REQUIRE(a.channel_names() == b.channel_names());
        for (const std::string &name : a.channel_names()) {
            INFO(name);
            CHECK(a.plane(a.index_of(name)) == b.plane(b.index_of(name)));
        }
    }
    // The same in one process: render --aovs maaf6 --filter aaf (its parameters refused before rendering).
    const std::string one = (dir / "one.exr").string(), baseline = (dir / "baseline.exr").string();
    const RunResult rendered =
        run_aaf("render room --aovs maaf6 --filter aaf --width 24 --height 18 --spp 4 -o " + one);
    REQUIRE(rendered.exit_code == 0);
    CHECK_THAT(rendered.output, Catch::Contains("aaf: note: room: a combined-effects render"));
    REQUIRE(run_aaf("filter maaf6 --pairs 1 " + render + " -o " + baseline).exit_code == 0);
    for (const char *name : {"R", "G", "B"}) {
        const aaf::AovSet a = aaf::io::read_aovs(one), b = aaf::io::read_aovs(baseline);
        CHECK(a.plane(a.index_of(name)) == b.plane(b.index_of(name)));
    }
    CHECK(run_aaf(
              "render room --aovs maaf6 --filter aaf --filter-param mu=3 --width 24 --height 18 --spp 4 -o " +
              (dir / "never.exr").string())
              .exit_code == 2);
    CHECK_FALSE(fs::exists(dir / "never.exr"));

    // An AAF option the delegate does not take: a usage error, as from render, one line naming it, nothing
    // written.
    const std::string refused = (dir / "refused.exr").string();
    const RunResult run = run_aaf("filter aaf --k 2 " + render + " -o " + refused);
    CHECK(run.exit_code == 2);
    CHECK_THAT(run.output, Catch::StartsWith("aaf: error: " + render) && Catch::Contains("aaf's --k"));
    CHECK(std::count(run.output.begin(), run.output.end(), '\n') == 1);
    CHECK_FALSE(fs::exists(refused));
}
