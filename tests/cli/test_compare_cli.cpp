#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "aaf/io/exr_io.h"
#include "run_aaf.h"

namespace fs = std::filesystem;
using aaf_test::run_aaf;
using aaf_test::scratch_dir;

namespace {

/// A 4x4 RGB image of one value.
void write_flat(const fs::path &path, float value) {
    aaf::AovSet image(4, 4);
    for (const char *c : {"R", "G", "B"}) image.add_channel(c, value);
    aaf::io::write_aovs(image, path.string());
}

}  // namespace

TEST_CASE("compare: batch over a 3-frame sequence with CSV and JSON", "[cli][compare]") {
    const fs::path dir = scratch_dir("compare_batch");
    // Frame f differs from its reference by 0.1 f: RMSE = 0.1 f, MAE = 0.1 f.
    for (int f = 1; f <= 3; ++f) {
        write_flat(dir / ("test." + std::to_string(1000 + f).substr(1) + ".exr"), 0.5f + 0.1f * f);
        write_flat(dir / ("ref." + std::to_string(1000 + f).substr(1) + ".exr"), 0.5f);
    }
    const std::string test = (dir / "test.###.exr").string(), ref = (dir / "ref.###.exr").string();
    const std::string csv = (dir / "out.csv").string();
    const auto result =
        run_aaf("compare " + test + " " + ref + " --frames 1-3 --metric rmse,mae --csv " + csv);
    REQUIRE(result.exit_code == 0);
    CHECK_THAT(result.output, Catch::Contains("median") && Catch::Contains("worst"));

    std::ifstream in(csv);
    std::string header, line;
    std::getline(in, header);
    CHECK(header == "label,test,reference,rmse,mae,pixels,nonfinite_pixels,spp");
    int rows = 0;
    while (std::getline(in, line)) {
        ++rows;
        std::stringstream fields(line);
        std::string label, t, r, rmse, mae;
        std::getline(fields, label, ',');
        std::getline(fields, t, ',');
        std::getline(fields, r, ',');
        std::getline(fields, rmse, ',');
        std::getline(fields, mae, ',');
        CHECK(std::stod(rmse) == Approx(0.1 * std::stoi(label)).epsilon(1e-5));
        CHECK(std::stod(mae) == Approx(0.1 * std::stoi(label)).epsilon(1e-5));
    }
    CHECK(rows == 3);

    const auto json_run =
        run_aaf("compare " + test + " " + ref + " --json --metric rmse");  // frames from disk
    REQUIRE(json_run.exit_code == 0);
    const nlohmann::json json = nlohmann::json::parse(json_run.output);
    REQUIRE(json["pairs"].size() == 3);
    CHECK(json["pairs"][1]["label"] == "2");
    CHECK(json["summary"]["rmse"]["mean"].get<double>() == Approx(0.2).epsilon(1e-5));
    CHECK(json["summary"]["rmse"]["median"].get<double>() == Approx(0.2).epsilon(1e-5));
    CHECK(json["summary"]["rmse"]["worst_label"] == "3");
}

TEST_CASE("compare: identical images report PSNR as null in JSON, SSIM 1, FLIP 0", "[cli][compare]") {
    const fs::path dir = scratch_dir("compare_identical");
    write_flat(dir / "a.exr", 0.25f);
    const auto run = run_aaf("compare " + (dir / "a.exr").string() + " " + (dir / "a.exr").string() +
                             " --json --metric mse,psnr,ssim,flip,flip_median");
    REQUIRE(run.exit_code == 0);
    const nlohmann::json json = nlohmann::json::parse(run.output);
    CHECK(json["mse"].get<double>() == 0.0);
    CHECK(json["psnr"].is_null());
    CHECK(json["ssim"].get<double>() == Approx(1.0));
    CHECK(json["flip"].get<double>() == 0.0);
    CHECK(json["flip_median"].get<double>() == 0.0);
}

TEST_CASE("compare: --fail-above and --fail-below set the exit code", "[cli][compare]") {
    const fs::path dir = scratch_dir("compare_gate");
    write_flat(dir / "test.exr", 0.6f);
    write_flat(dir / "ref.exr", 0.5f);
    const std::string pair = (dir / "test.exr").string() + " " + (dir / "ref.exr").string();
    CHECK(run_aaf("compare " + pair + " --fail-above rmse=0.2").exit_code == 0);
    const auto failed = run_aaf("compare " + pair + " --fail-above rmse=0.05");
    CHECK(failed.exit_code == 4);
    CHECK_THAT(failed.output, Catch::Contains("rmse") && Catch::Contains("above"));
    CHECK(run_aaf("compare " + pair + " --fail-below psnr=25").exit_code == 4);  // PSNR is 20 dB
    CHECK(run_aaf("compare " + pair + " --fail-below psnr=15").exit_code == 0);
    CHECK(run_aaf("compare " + pair + " --fail-above nonsense=1").exit_code == 2);
}

TEST_CASE("compare: heatmap PNG and EXR, NaN pixels counted", "[cli][compare]") {
    const fs::path dir = scratch_dir("compare_heatmap");
    aaf::AovSet test(4, 4);
    for (const char *c : {"R", "G", "B"}) test.add_channel(c, 0.5f);
    test.channel("R")(2, 2) = std::nanf("");
    aaf::io::write_aovs(test, (dir / "test.exr").string());
    write_flat(dir / "ref.exr", 0.5f);
    const auto run = run_aaf("compare " + (dir / "test.exr").string() + " " + (dir / "ref.exr").string() +
                             " --heatmap " + (dir / "heat.png").string());
    REQUIRE(run.exit_code == 0);
    CHECK_THAT(run.output, Catch::Contains("1 NaN/Inf pixels skipped"));
    CHECK(fs::exists(dir / "heat.png"));
    const aaf::AovSet heat = aaf::io::read_aovs((dir / "heat.exr").string());
    CHECK(heat.channel("error.rms")(0, 0) == 0.0f);
    CHECK(std::isnan(heat.channel("error.rms")(2, 2)));
}
