#include <catch2/catch.hpp>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "aaf/core/analysis/wedge_metrics.h"
#include "run_aaf.h"

using aaf_test::run_aaf;
using aaf_test::RunResult;

namespace {

nlohmann::json run_json(const std::string &args) {
    const RunResult result = run_aaf(args + " --json");
    REQUIRE(result.exit_code == 0);
    return nlohmann::json::parse(result.output);
}

std::vector<std::string> keys_of(const nlohmann::json &object) {
    std::vector<std::string> keys;
    for (auto it = object.begin(); it != object.end(); ++it) keys.push_back(it.key());
    std::sort(keys.begin(), keys.end());
    return keys;
}

}  // namespace

TEST_CASE(
    "CLI: analyze wedge --json is keyed by the paper's method names, box coverage equal to MAAF Eq. 16-18",
    "[cli][analyze]") {
    const nlohmann::json out =
        run_json("analyze wedge --smin 0.7 --smax 2.2 --filters 1,2,3,4,13,38,63 --box");
    CHECK(keys_of(out) == std::vector<std::string>{"AAF", "FSF", "MAAF(1)", "MAAF(125)", "MAAF(25)",
                                                   "MAAF(3)", "MAAF(5)", "MAAF(7)", "MAAF(75)"});
    const aaf::DoubleWedge wedge{0.7, 2.2, 1};
    CHECK(out["AAF"]["coverage_eq16_18"].get<double>() == Approx(aaf::aaf_box_coverage(wedge)));
    CHECK(out["FSF"]["coverage_eq16_18"].get<double>() == 0.5);
    CHECK(out["MAAF(5)"]["coverage_eq16_18"].get<double>() == Approx(aaf::maaf_box_coverage(wedge, 3)));
    double previous = 0;
    for (const char *name :
         {"MAAF(1)", "MAAF(3)", "MAAF(5)", "MAAF(7)", "MAAF(25)", "MAAF(75)", "MAAF(125)"}) {
        CAPTURE(name);
        const nlohmann::json &m = out[name];
        // The default 1024 x 1024 grid: within 1% of the closed form, boxes cover T exactly.
        CHECK(m["coverage"].get<double>() == Approx(m["coverage_eq16_18"].get<double>()).epsilon(0.01));
        CHECK(m["accuracy"].get<double>() == Approx(1.0));
        CHECK(m["coverage_eq16_18"].get<double>() > previous);
        previous = m["coverage_eq16_18"].get<double>();
    }
    CHECK(out["MAAF(1)"]["coverage"].get<double>() == out["AAF"]["coverage"].get<double>());
}

TEST_CASE("CLI: analyze wedge --random averages the same wedges for a seed, and --gauss has accuracy below 1",
          "[cli][analyze]") {
    const std::string args = "analyze wedge --random 5 --seed 3 --grid 128 --filters 2,3";
    const nlohmann::json a = run_json(args), b = run_json(args);
    CHECK(a == b);
    CHECK(keys_of(a) == std::vector<std::string>{"AAF", "FSF", "MAAF(3)", "MAAF(5)"});
    CHECK(a != run_json("analyze wedge --random 5 --seed 4 --grid 128 --filters 2,3"));
    const nlohmann::json g = run_json("analyze wedge --smin 0.5 --smax 0.8 --gauss --grid 256");
    CHECK(keys_of(g) == std::vector<std::string>{"AAF", "FSF", "MAAF(3)", "MAAF(5)", "MAAF(7)"});
    for (const auto &item : g.items()) {
        CAPTURE(item.key());
        CHECK(item.value()["accuracy"].get<double>() < 1.0);
        CHECK(item.value()["coverage"].get<double>() > 0.0);
        CHECK_FALSE(item.value().contains("coverage_eq16_18"));
    }
    const RunResult text = run_aaf("analyze wedge --random 3 --grid 64");
    CHECK(text.exit_code == 0);
    CHECK_THAT(text.output, Catch::Contains("paper Table 1") && Catch::Contains("0.097"));
}

TEST_CASE("CLI: analyze wedge refuses meaningless wedges and options with one line and exit 2",
          "[cli][analyze]") {
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"analyze wedge --smin 2 --smax 1", "--smin 2 must be below --smax 1"},
        {"analyze wedge --smin 1 --smax 1", "must be below"},
        {"analyze wedge --smin -1 --smax 1", "--smin"},
        {"analyze wedge --smin 0 --smax 1", "--smin"},
        {"analyze wedge --smin nan --smax 1", "--smin"},
        {"analyze wedge --smin 1 --smax 2 --filters 0", "--filters"},
        {"analyze wedge --smin 1", "give --smin and --smax"},
        {"analyze wedge --smin 1 --smax 2 --random 5", "--random"},
        {"analyze wedge --smin 1 --smax 2 --box --gauss", "--box"},
        {"analyze wedge --smin 1 --smax 2 --grid 101", "--grid 101 must be even"},
        {"analyze wedge --smin 1 --smax 2 --no-mu", "--no-mu"},
        {"analyze wedges", "unknown subcommand 'wedges'"},
    };
    for (const auto &command : cases) {
        CAPTURE(command.first);
        const RunResult result = run_aaf(command.first);
        CHECK(result.exit_code == 2);
        CHECK_THAT(result.output, Catch::Contains(command.second));
        CHECK(std::count(result.output.begin(), result.output.end(), '\n') == 1);
    }
}
