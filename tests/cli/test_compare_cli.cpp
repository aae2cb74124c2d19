#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "aaf/io/exr_io.h"
#include "flat_image.h"
#include "run_aaf.h"

namespace fs = std::filesystem;
using aaf_test::run_aaf;
using aaf_test::scratch_dir;
using aaf_test::write_flat;

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
    CHECK(header == "label,test,reference,rmse,mae,pixels,nonfinite_pixels,spp,psnr_peak");
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
    // Usage errors exit 2: inputs that do not pair up, --frames without patterns.
    CHECK(run_aaf("compare " + pair + " --frames 1-3").exit_code == 2);
    CHECK(run_aaf("compare " + (dir / "test.exr").string() + " " + dir.string()).exit_code == 2);
    CHECK(run_aaf("compare " + (dir / "t.####.exr").string() + " " + (dir / "ref.exr").string()).exit_code ==
          2);
    CHECK(run_aaf("compare " + (dir / "t.####.exr").string() + " " + (dir / "r.####.exr").string() +
                  " --frames 3-1")
              .exit_code == 2);
    // An input problem exits 3: no frames on disk.
    CHECK(
        run_aaf("compare " + (dir / "t.####.exr").string() + " " + (dir / "r.####.exr").string()).exit_code ==
        3);
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

namespace {

/// A width x height RGB image whose channels are all value(x, y).
template <typename Fn>
void write_pattern(const fs::path &path, int width, int height, const Fn &value) {
    aaf::AovSet image(width, height);
    for (const char *c : {"R", "G", "B"}) {
        aaf::PlaneView plane = image.add_channel(c);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) plane(x, y) = value(x, y);
    }
    aaf::io::write_aovs(image, path.string());
}

}  // namespace

TEST_CASE("compare: an output that is an input is refused with exit 3, the input untouched",
          "[cli][compare]") {
    const fs::path dir = scratch_dir("compare_overwrite");
    write_flat(dir / "x.exr", 0.6f);
    write_flat(dir / "ref.exr", 0.5f);
    const std::string x = (dir / "x.exr").string(), ref = (dir / "ref.exr").string();
    // --heatmap x.png writes its EXR to x.exr: the test image.
    const auto heatmap = run_aaf("compare " + x + " " + ref + " --heatmap " + (dir / "x.png").string());
    CHECK(heatmap.exit_code == 3);
    CHECK(heatmap.output == "aaf: error: " + x + ": output would overwrite the input\n");
    CHECK_FALSE(fs::exists(dir / "x.png"));
    // The heatmap PNG itself, and the CSV, onto the reference.
    const auto png = run_aaf("compare " + x + " " + ref + " --heatmap " + ref);
    CHECK(png.exit_code == 2);  // a PNG name ending in .exr is a usage error
    const auto csv = run_aaf("compare " + x + " " + ref + " --csv " + ref);
    CHECK(csv.exit_code == 3);
    CHECK(csv.output == "aaf: error: " + ref + ": output would overwrite the input\n");
    const auto csv_test = run_aaf("compare " + x + " " + ref + " --csv " + x);
    CHECK(csv_test.exit_code == 3);
    // Inputs unchanged: still RGB images of their values, no heatmap channel.
    const aaf::AovSet x_after = aaf::io::read_aovs(x), ref_after = aaf::io::read_aovs(ref);
    CHECK_FALSE(x_after.has_channel("error.rms"));
    CHECK(x_after.channel("R")(1, 1) == 0.6f);
    CHECK(ref_after.channel("G")(1, 1) == 0.5f);

    // A batch: the CSV onto one frame of the reference sequence.
    write_flat(dir / "t.1.exr", 0.6f);
    write_flat(dir / "r.1.exr", 0.5f);
    const auto batch = run_aaf("compare " + (dir / "t.#.exr").string() + " " + (dir / "r.#.exr").string() +
                               " --csv " + (dir / "r.1.exr").string());
    CHECK(batch.exit_code == 3);
    CHECK_THAT(batch.output, Catch::Contains("r.1.exr: output would overwrite the input"));
    CHECK(aaf::io::read_aovs((dir / "r.1.exr").string()).has_channel("R"));
}

TEST_CASE("compare: a batch matching one pair keeps the batch shape, two files keep the object",
          "[cli][compare]") {
    const fs::path dir = scratch_dir("compare_shape");
    for (int f = 1; f <= 3; ++f) {
        write_flat(dir / ("test." + std::to_string(f) + ".exr"), 0.5f + 0.1f * f);
        write_flat(dir / ("ref." + std::to_string(f) + ".exr"), 0.5f);
    }
    const std::string test = (dir / "test.#.exr").string(), ref = (dir / "ref.#.exr").string();
    const auto one_frame = run_aaf("compare " + test + " " + ref + " --frames 2 --json --metric rmse");
    REQUIRE(one_frame.exit_code == 0);
    const nlohmann::json batch = nlohmann::json::parse(one_frame.output);
    REQUIRE(batch["pairs"].size() == 1);
    CHECK(batch["pairs"][0]["label"] == "2");
    CHECK(batch["summary"]["rmse"]["worst_label"] == "2");
    CHECK(batch["summary"]["rmse"]["mean"].get<double>() == Approx(0.2).epsilon(1e-5));
    CHECK_FALSE(batch.contains("rmse"));
    const auto one_frame_table = run_aaf("compare " + test + " " + ref + " --frames 2 --metric rmse");
    CHECK_THAT(one_frame_table.output, Catch::Contains("worst pair"));

    // Two folders with one file name in common.
    fs::create_directories(dir / "a");
    fs::create_directories(dir / "b");
    write_flat(dir / "a" / "only.exr", 0.7f);
    write_flat(dir / "b" / "only.exr", 0.5f);
    const auto folders = run_aaf("compare " + (dir / "a").string() + " " + (dir / "b").string() + " --json");
    REQUIRE(folders.exit_code == 0);
    CHECK(nlohmann::json::parse(folders.output)["pairs"].size() == 1);

    const auto files = run_aaf("compare " + (dir / "test.1.exr").string() + " " +
                               (dir / "ref.1.exr").string() + " --json --metric rmse");
    REQUIRE(files.exit_code == 0);
    const nlohmann::json single = nlohmann::json::parse(files.output);
    CHECK_FALSE(single.contains("pairs"));
    CHECK(single["rmse"].get<double>() == Approx(0.1).epsilon(1e-5));
}

TEST_CASE("compare: the table's worst pair row names each metric's worst frame", "[cli][compare]") {
    const fs::path dir = scratch_dir("compare_worst_row");
    // RMSE is worst at frame 2 (error 0.3); PSNR (higher is better) is then also worst at frame 2.
    const float errors[] = {0.1f, 0.3f, 0.2f};
    for (int f = 1; f <= 3; ++f) {
        write_flat(dir / ("test." + std::to_string(f) + ".exr"), 0.5f + errors[f - 1]);
        write_flat(dir / ("ref." + std::to_string(f) + ".exr"), 0.5f);
    }
    const auto run = run_aaf("compare " + (dir / "test.#.exr").string() + " " + (dir / "ref.#.exr").string() +
                             " --metric rmse,psnr");
    REQUIRE(run.exit_code == 0);
    std::stringstream lines(run.output);
    std::string line, worst_pair;
    while (std::getline(lines, line))
        if (line.rfind("worst pair", 0) == 0) worst_pair = line;
    std::stringstream fields(worst_pair.substr(std::string("worst pair").size()));
    std::string rmse_label, psnr_label;
    fields >> rmse_label >> psnr_label;
    CHECK(rmse_label == "2");
    CHECK(psnr_label == "2");
}

TEST_CASE("compare: a mask of another size names the mask file, a missing layer exits 3", "[cli][compare]") {
    const fs::path dir = scratch_dir("compare_input_errors");
    write_flat(dir / "test.exr", 0.6f);
    write_flat(dir / "ref.exr", 0.5f);
    aaf::AovSet mask(2, 2);
    mask.add_channel("A", 1.0f);
    aaf::io::write_aovs(mask, (dir / "mask.exr").string());
    const std::string pair = (dir / "test.exr").string() + " " + (dir / "ref.exr").string();
    const auto sized = run_aaf("compare " + pair + " --mask " + (dir / "mask.exr").string());
    CHECK(sized.exit_code == 3);
    CHECK_THAT(sized.output, Catch::StartsWith("aaf: error: " + (dir / "mask.exr").string() + ": ") &&
                                 Catch::Contains("2x2") && Catch::Contains("4x4"));
    const auto layer = run_aaf("compare " + pair + " --layer nosuchlayer");
    CHECK(layer.exit_code == 3);
    CHECK_THAT(layer.output, Catch::Contains("no channels in layer 'nosuchlayer'"));
    const auto channel = run_aaf("compare " + pair + " --channels R,Q");
    CHECK(channel.exit_code == 3);  // the missing channel, for comparison: the same exit code
}

TEST_CASE("compare: the heatmap covers the crop and shows masked-out pixels black", "[cli][compare]") {
    const fs::path dir = scratch_dir("compare_heatmap_region");
    // Test - reference = 0.01 (x + 10 y): every pixel's RMS error differs.
    write_pattern(dir / "test.exr", 8, 6, [](int x, int y) { return 0.5f + 0.01f * float(x + 10 * y); });
    write_pattern(dir / "ref.exr", 8, 6, [](int, int) { return 0.5f; });
    aaf::AovSet mask(8, 6);
    aaf::PlaneView keep = mask.add_channel("A", 1.0f);
    keep(3, 2) = 0.0f;  // inside the crop below, at (1, 1) of the heatmap
    aaf::io::write_aovs(mask, (dir / "mask.exr").string());
    const auto run = run_aaf("compare " + (dir / "test.exr").string() + " " + (dir / "ref.exr").string() +
                             " --crop 2,1,4,3 --mask " + (dir / "mask.exr").string() + " --heatmap " +
                             (dir / "heat.png").string());
    REQUIRE(run.exit_code == 0);
    const aaf::AovSet heat = aaf::io::read_aovs((dir / "heat.exr").string());
    REQUIRE(heat.width() == 4);
    REQUIRE(heat.height() == 3);
    CHECK(heat.channel("error.rms")(0, 0) == Approx(0.01f * (2 + 10 * 1)).epsilon(1e-4));
    CHECK(heat.channel("error.rms")(3, 2) == Approx(0.01f * (5 + 10 * 3)).epsilon(1e-4));
    CHECK(heat.channel("error.compared")(1, 1) == 0.0f);
    CHECK(heat.channel("error.compared")(0, 0) == 1.0f);
    CHECK(heat.channel("error.rms")(1, 1) == 0.0f);

    const aaf::AovSet png = aaf::io::read_aovs((dir / "heat.png").string());
    CHECK(png.height() == 3);
    CHECK(png.width() == 4 + 4 + 16);  // the crop, a gap and the colour bar (too low for labels)
    for (const char *c : {"R", "G", "B"}) {
        CHECK(png.channel(c)(1, 1) == 0.0f);  // masked out: black
    }
    CHECK(png.channel("B")(0, 0) > 0.0f);  // the ramp's lowest colour is dark blue, not black
}

TEST_CASE("compare: the heatmap PNG carries its scale in its metadata", "[cli][compare]") {
    const fs::path dir = scratch_dir("compare_heatmap_scale");
    write_pattern(dir / "test.exr", 64, 48, [](int x, int) { return 0.5f + 0.001f * float(x); });
    write_pattern(dir / "ref.exr", 64, 48, [](int, int) { return 0.5f; });
    const auto run = run_aaf("compare " + (dir / "test.exr").string() + " " + (dir / "ref.exr").string() +
                             " --heatmap " + (dir / "heat.png").string());
    REQUIRE(run.exit_code == 0);
    const aaf::AovSet png = aaf::io::read_aovs((dir / "heat.png").string());
    CHECK(png.width() == 64 + 4 + 16 + 4 + 64);  // image, gap, bar, gap, label column
    REQUIRE(png.attributes.count("ImageDescription"));
    // 99th percentile of 0.001 x over x in 0..63, 48 rows alike: sorted index 3040 of 3072, x = 63.
    CHECK_THAT(std::get<std::string>(png.attributes.at("ImageDescription")),
               Catch::Contains("colour bar 0 to 0.063"));
}

TEST_CASE(
    "compare: a sequence's temporal error is the RMSE of the frame-to-frame change of its error, 0 for a "
    "still error, undefined for the first frame, and a single pair refuses it",
    "[cli][compare]") {
    const fs::path dir = scratch_dir("compare_temporal");
    // Flickering: frame f's error is 0.1 f, so it changes by 0.1 a frame.
    // Still: every frame is 0.2 off, an error that never changes.
    for (int f = 1; f <= 3; ++f) {
        const std::string frame = std::to_string(1000 + f).substr(1);
        write_flat(dir / ("flicker." + frame + ".exr"), 0.5f + 0.1f * f);
        write_flat(dir / ("still." + frame + ".exr"), 0.7f);
        write_flat(dir / ("ref." + frame + ".exr"), 0.5f);
    }
    const std::string flicker = (dir / "flicker.###.exr").string(), still = (dir / "still.###.exr").string(),
                      ref = (dir / "ref.###.exr").string();

    // A sequence gets it beside the default metrics: null for the first frame.
    const auto json_run = run_aaf("compare " + flicker + " " + ref + " --json");
    REQUIRE(json_run.exit_code == 0);
    const nlohmann::json json = nlohmann::json::parse(json_run.output);
    REQUIRE(json["pairs"].size() == 3);
    CHECK(json["pairs"][0]["temporal_rmse"].is_null());
    CHECK(json["pairs"][1]["temporal_rmse"].get<double>() == Approx(0.1).epsilon(1e-5));
    CHECK(json["pairs"][2]["temporal_rmse"].get<double>() == Approx(0.1).epsilon(1e-5));
    CHECK(json["summary"]["temporal_rmse"]["mean"].get<double>() == Approx(0.1).epsilon(1e-5));
    CHECK(json["summary"]["temporal_rmse"]["worst_label"] != "1");
    CHECK(json["pairs"][2]["rmse"].get<double>() == Approx(0.3).epsilon(1e-5));

    const std::string csv = (dir / "still.csv").string();
    const auto still_run =
        run_aaf("compare " + still + " " + ref + " --metric rmse,temporal_rmse --csv " + csv);
    REQUIRE(still_run.exit_code == 0);
    CHECK_THAT(still_run.output, Catch::Contains("temporal"));
    std::ifstream in(csv);
    std::string header, first, second;
    std::getline(in, header);
    std::getline(in, first);
    std::getline(in, second);
    CHECK(header == "label,test,reference,rmse,temporal_rmse,pixels,nonfinite_pixels,spp,psnr_peak");
    CHECK_THAT(first, Catch::Contains(",,16,"));  // no temporal error for frame 1
    CHECK_THAT(second, Catch::Contains(",0,16,"));

    // A gate on it skips the first frame and catches the flicker.
    CHECK(run_aaf("compare " + still + " " + ref + " --fail-above temporal_rmse=0.01").exit_code == 0);
    CHECK(run_aaf("compare " + flicker + " " + ref + " --fail-above temporal_rmse=0.05").exit_code == 4);

    const auto single = run_aaf("compare " + (dir / "still.001.exr").string() + " " +
                                (dir / "ref.001.exr").string() + " --metric temporal_rmse");
    CHECK(single.exit_code == 2);
    CHECK_THAT(single.output, Catch::Contains("temporal_rmse"));
}
