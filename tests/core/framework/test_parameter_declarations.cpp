// ParameterDeclarations: each parameter declared once, bound to the settings
// member it sets, its default the text of that member's initialiser.
#include <catch2/catch.hpp>

#include <set>
#include <string>
#include <vector>

#include "aaf/core/framework/method_registry.h"
#include "aaf/core/framework/parameter_defaults.h"
#include "aaf/core/framework/parameters.h"
#include "aaf/core/methods/aaf/aaf_filter.h"
#include "aaf/core/util/error.h"

using namespace aaf;

namespace {

enum class Shape { Square, Disc };

struct ToySettings {
    float scale = 2.0f;
    float sigma = 1e-3f;
    float alpha = 0.2f;
    double spp = 128;
    int radius_px = 25;
    std::uint32_t seed = 0;
    bool fast = false;
    bool symmetric = true;
    Shape shape = Shape::Disc;
    std::string denoiser = "bilateral";
};

ParameterDeclarations<ToySettings> toy_declarations() {
    using P = ToySettings;
    return std::move(ParameterDeclarations<P>("toy")
                         .real("scale", &P::scale, "", "", 0, 10, /*min_open=*/true)
                         .real("sigma", &P::sigma, "", "", 0, 1)
                         .real("alpha", &P::alpha, "", "", 0, 1)
                         .real("spp", &P::spp, "spp", "", 0)
                         .integer("radius", &P::radius_px, "pixels", "", 0, 64)
                         .integer("seed", &P::seed, "", "", 0, 1 << 30)
                         .flag("fast", &P::fast, "")
                         .choice("borders", &P::symmetric, {{"symmetric", true}, {"clip", false}}, "")
                         .choice("shape", &P::shape, {{"square", Shape::Square}, {"disc", Shape::Disc}}, "")
                         .text_choice("denoiser", &P::denoiser, {"bilateral", "gaussian"}, ""));
}

std::string default_of(const std::vector<ParameterInfo> &infos, const std::string &name) {
    for (const ParameterInfo &info : infos)
        if (info.name == name) return info.default_value;
    FAIL("no parameter " << name);
    return {};
}

}  // namespace

TEST_CASE(
    "Parameters: every built-in method's declared defaults read back as its settings struct's "
    "default member initialisers",
    "[core][parameters]") {
    std::set<std::string> checked;
    for (const auto &method : builtin_parameter_defaults_read_back_differently()) {
        INFO(method.first);
        CHECK(method.second.empty());  // the names of those that differ
        checked.insert(method.first);
        // The declarations checked are the ones the registered method shows.
        CHECK_FALSE(find_method(method.first).info().parameters.empty());
    }
    // Every registered built-in method with parameters is among them (plugins register after them).
    for (const Method *method : methods())
        if (!method->info().parameters.empty() && method->info().name.find("toy") == std::string::npos)
            CHECK(checked.count(method->info().name) == 1);
}

TEST_CASE(
    "Parameters: a declared default is the text of its member's initialiser, as --help, aaf info and "
    "provenance print it",
    "[core][parameters]") {
    const ParameterDeclarations<ToySettings> toy = toy_declarations();
    const std::vector<ParameterInfo> &infos = toy.infos();
    CHECK(default_of(infos, "scale") == "2");
    CHECK(default_of(infos, "sigma") == "0.001");  // not 0.00100000005 (the float's %.9g)
    CHECK(default_of(infos, "alpha") == "0.2");
    CHECK(default_of(infos, "spp") == "128");  // not 1.3e+02
    CHECK(default_of(infos, "radius") == "25");
    CHECK(default_of(infos, "seed") == "0");
    CHECK(default_of(infos, "fast") == "false");
    CHECK(default_of(infos, "borders") == "symmetric");
    CHECK(default_of(infos, "shape") == "disc");
    CHECK(default_of(infos, "denoiser") == "bilateral");
    CHECK(toy.defaults_read_back_differently().empty());
    // AAF's, as they have always printed.
    const std::vector<ParameterInfo> &aaf = aaf_parameter_declarations().infos();
    CHECK(default_of(aaf, "mu") == "2");
    CHECK(default_of(aaf, "normal_threshold") == "25");
    CHECK(default_of(aaf, "fixed_beta") == "0");
    CHECK(default_of(aaf, "light_bandlimit") == "sigma");
    CHECK(default_of(aaf, "pixel_footprint") == "receiver");
    CHECK(default_of(aaf, "mu_from_spp") == "false");
}

TEST_CASE("Parameters: a struct written to a set reads back member for member", "[core][parameters]") {
    const ParameterDeclarations<ToySettings> toy = toy_declarations();
    ToySettings p;
    p.scale = 0.3f;
    p.sigma = 0.123456789f;
    p.spp = 0.1;
    p.radius_px = 7;
    p.seed = 12345;
    p.fast = true;
    p.symmetric = false;
    p.shape = Shape::Square;
    p.denoiser = "gaussian";
    const ParameterSet set = toy.write(p);
    CHECK(set.text("scale") == "0.3");  // what a user types, not 0.300000012
    CHECK(set.text("borders") == "clip");
    const ToySettings q = toy.read(set);
    CHECK(q.scale == p.scale);
    CHECK(q.sigma == p.sigma);
    CHECK(q.spp == double(0.1f));  // reals are read at float precision, as ParameterSet::get_float
    CHECK(q.radius_px == 7);
    CHECK(q.seed == 12345);
    CHECK(q.fast);
    CHECK_FALSE(q.symmetric);
    CHECK(q.shape == Shape::Square);
    CHECK(q.denoiser == "gaussian");
    // A value out of its declared range is refused when written, naming the parameter.
    p.scale = 0;
    CHECK_THROWS_WITH(toy.write(p), Catch::Contains("'scale'"));

    AafParams aaf;
    aaf.mu = 0.3f;
    aaf.light_axes = AafLightAxes::Shortest;
    aaf.light_distance = AafLightDistance::Guarded;
    aaf.projected_pixel = true;
    aaf.symmetric_borders = false;
    aaf.fill_radius_px = 3;
    const AafParams back = aaf_parameter_declarations().read(aaf_parameter_set(aaf));
    CHECK(back.mu == aaf.mu);
    CHECK(back.light_axes == aaf.light_axes);
    CHECK(back.light_distance == aaf.light_distance);
    CHECK(back.projected_pixel);
    CHECK_FALSE(back.symmetric_borders);
    CHECK(back.fill_radius_px == 3);
}

TEST_CASE("Parameters: a default its declaration cannot name is refused when declared",
          "[core][parameters]") {
    struct Drifted {
        Shape shape = Shape::Disc;
    };
    // The choices list no name for the initialiser's value: no default text could say it.
    CHECK_THROWS_AS(ParameterDeclarations<Drifted>("drifted").choice("shape", &Drifted::shape,
                                                                     {{"square", Shape::Square}}, ""),
                    Error);
    // A default outside the declared range is refused too (the set of defaults is not valid).
    struct OutOfRange {
        float mu = 0;
    };
    ParameterDeclarations<OutOfRange> out("out");
    out.real("mu", &OutOfRange::mu, "", "", 0, 10, /*min_open=*/true);
    CHECK_THROWS_WITH(out.defaults(), Catch::Contains("'mu'"));
}

TEST_CASE("Parameters: the plan shares AAF's mu, light band-limit, light axes and pixel footprint",
          "[core][parameters]") {
    const std::vector<std::string> expected = {"mu", "light_bandlimit", "light_axes", "pixel_footprint"};
    CHECK(aaf_plan_parameter_names() == expected);
    for (const std::string &name : aaf_plan_parameter_names())
        CHECK_NOTHROW(aaf_parameter_declarations().info(name));
    CHECK_THROWS_WITH(aaf_parameter_declarations().info("nu"), Catch::Contains("mu"));
}
