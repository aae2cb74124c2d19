// `aaf compare` on filter outputs: channel mappings, the beauty through the
// role table, layers of mixed units, unmatched batch files, CSV quoting, the
// PSNR's peak in every output, batch progress.
#include <catch2/catch.hpp>

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "aaf/core/contract/aov_set.h"
#include "aaf/io/exr_io.h"
#include "flat_image.h"
#include "run_aaf.h"

namespace fs = std::filesystem;
using aaf_test::run_aaf;
using aaf_test::scratch_dir;
using aaf_test::write_flat;

namespace {

/// A 4x4 image holding each channel of `values` at that value.
void write_channels(const fs::path &path, const std::map<std::string, float> &values) {
    aaf::AovSet image(4, 4);
    for (const auto &entry : values) image.add_channel(entry.first, entry.second);
    aaf::io::write_aovs(image, path.string());
}

struct SplitRun {
    int exit_code;
    std::string out, err;
};

/// Runs aaf with stdout and stderr apart (run_aaf merges them).
SplitRun run_split(const std::string &args, const fs::path &dir) {
    const fs::path out = dir / "stdout.txt", err = dir / "stderr.txt";
    const int status = std::system(
        (std::string(AAF_EXECUTABLE) + " " + args + " >" + out.string() + " 2>" + err.string()).c_str());
    std::stringstream o, e;
    o << std::ifstream(out).rdbuf();
    e << std::ifstream(err).rdbuf();
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, o.str(), e.str()};
}

double json_rmse(const std::string &args) {
    const auto run = run_aaf("compare " + args + " --json --metric rmse");
    REQUIRE(run.exit_code == 0);
    return nlohmann::json::parse(run.output)["rmse"].get<double>();
}

}  // namespace

TEST_CASE("compare: --channels test=reference measures a filter's output against the reference's channel",
          "[cli][compare]") {
    const fs::path dir = scratch_dir("compare_mapping");
    write_channels(dir / "filtered.exr", {{"aaf.V", 0.7f}, {"shadow.V", 0.2f}});
    write_channels(dir / "reference.exr", {{"shadow.V", 0.5f}});
    const std::string pair = (dir / "filtered.exr").string() + " " + (dir / "reference.exr").string();
    // aaf.V (0.7) against the reference's shadow.V (0.5), not the test's own shadow.V (0.2).
    CHECK(json_rmse(pair + " --channels aaf.V=shadow.V") == Approx(0.2).epsilon(1e-6));
    const auto run = run_aaf("compare " + pair + " --channels aaf.V=shadow.V --json");
    CHECK(nlohmann::json::parse(run.output)["channels"] == nlohmann::json{"aaf.V=shadow.V"});
    const auto missing = run_aaf("compare " + pair + " --channels aaf.V=nosuch.V");
    CHECK(missing.exit_code == 3);
    CHECK_THAT(missing.output,
               Catch::Contains((dir / "reference.exr").string()) && Catch::Contains("nosuch.V"));
}

TEST_CASE("compare: the default R,G,B find a Blender file's ViewLayer.Combined beauty", "[cli][compare]") {
    const fs::path dir = scratch_dir("compare_blender_beauty");
    write_channels(dir / "blender.exr", {{"ViewLayer.Combined.R", 0.8f},
                                         {"ViewLayer.Combined.G", 0.8f},
                                         {"ViewLayer.Combined.B", 0.8f},
                                         {"ViewLayer.Combined.A", 1.0f}});
    write_flat(dir / "reference.exr", 0.5f);
    CHECK(json_rmse((dir / "blender.exr").string() + " " + (dir / "reference.exr").string()) ==
          Approx(0.3).epsilon(1e-6));
    // Either side: the reference may be the Blender file.
    CHECK(json_rmse((dir / "reference.exr").string() + " " + (dir / "blender.exr").string()) ==
          Approx(0.3).epsilon(1e-6));
}

TEST_CASE("compare: --layer refuses to average visibility with metres, and names a way out",
          "[cli][compare]") {
    const fs::path dir = scratch_dir("compare_layer_units");
    const std::map<std::string, float> shadow{
        {"shadow.V", 0.5f}, {"shadow.d1", 3.0f}, {"shadow.d2min", 1.0f}, {"shadow.d2max", 2.0f}};
    write_channels(dir / "a.exr", shadow);
    write_channels(dir / "b.exr", shadow);
    const auto run =
        run_aaf("compare " + (dir / "a.exr").string() + " " + (dir / "b.exr").string() + " --layer shadow");
    CHECK(run.exit_code == 3);
    CHECK_THAT(run.output, Catch::StartsWith("aaf: error: " + (dir / "a.exr").string()) &&
                               Catch::Contains("metres") && Catch::Contains("--channels shadow.V"));
    // A layer of one kind still compares as a whole.
    write_channels(dir / "c.exr", {{"noisy.R", 0.6f}, {"noisy.G", 0.6f}, {"noisy.B", 0.6f}});
    write_channels(dir / "d.exr", {{"noisy.R", 0.5f}, {"noisy.G", 0.5f}, {"noisy.B", 0.5f}});
    CHECK(json_rmse((dir / "c.exr").string() + " " + (dir / "d.exr").string() + " --layer noisy") ==
          Approx(0.1).epsilon(1e-5));
}

TEST_CASE("compare: batch folders list unmatched files, and --fail-unmatched exits 4 after the results",
          "[cli][compare]") {
    const fs::path dir = scratch_dir("compare_unmatched");
    fs::create_directories(dir / "test");
    fs::create_directories(dir / "ref");
    write_flat(dir / "test" / "a.exr", 0.6f);
    write_flat(dir / "ref" / "a.exr", 0.5f);
    write_flat(dir / "test" / "only_test.exr", 0.5f);
    write_flat(dir / "ref" / "only_ref.exr", 0.5f);
    const std::string dirs = (dir / "test").string() + " " + (dir / "ref").string();
    const auto listed = run_aaf("compare " + dirs);
    CHECK(listed.exit_code == 0);
    CHECK_THAT(listed.output, Catch::Contains((dir / "test" / "only_test.exr").string()) &&
                                  Catch::Contains((dir / "ref" / "only_ref.exr").string()));
    const SplitRun json = run_split("compare " + dirs + " --json", dir);
    REQUIRE(json.exit_code == 0);
    CHECK(nlohmann::json::parse(json.out)["unmatched"].size() == 2);
    const auto failed = run_aaf("compare " + dirs + " --fail-unmatched");
    CHECK(failed.exit_code == 4);
    CHECK_THAT(failed.output, Catch::Contains("a.exr") && Catch::Contains("2 unmatched"));
}

TEST_CASE(
    "compare: CSV fields with a comma or quote are quoted per RFC 4180 and the PSNR peak is in every output",
    "[cli][compare]") {
    const fs::path dir = scratch_dir("compare_csv_quoting");
    fs::create_directories(dir / "test");
    fs::create_directories(dir / "ref");
    const std::string name = "shot,\"take 2\".exr";
    write_flat(dir / "test" / name, 0.6f);
    write_flat(dir / "ref" / name, 0.5f);
    const std::string dirs = "'" + (dir / "test").string() + "' '" + (dir / "ref").string() + "'";
    const std::string csv = (dir / "out.csv").string();
    REQUIRE(run_aaf("compare " + dirs + " --metric rmse,psnr --peak 2 --csv " + csv).exit_code == 0);
    std::ifstream in(csv);
    std::string header, row;
    std::getline(in, header);
    std::getline(in, row);
    CHECK(header == "label,test,reference,rmse,psnr,pixels,nonfinite_pixels,spp,psnr_peak");
    CHECK(
        row.rfind("\"shot,\"\"take 2\"\".exr\",\"" + (dir / "test").string() + "/shot,\"\"take 2\"\".exr\",",
                  0) == 0);
    CHECK(row.substr(row.rfind(',') + 1) == "2");

    const std::string pair = (dir / "test" / name).string(), ref = (dir / "ref" / name).string();
    const auto line = run_aaf("compare '" + pair + "' '" + ref + "' --metric psnr --peak 2");
    CHECK_THAT(line.output, Catch::Contains("dB (peak 2)"));
    const auto json = run_aaf("compare '" + pair + "' '" + ref + "' --metric psnr --peak 2 --json");
    CHECK(nlohmann::json::parse(json.output)["psnr_peak"].get<double>() == 2.0);
    const auto table = run_aaf("compare " + dirs + " --metric psnr --peak 2");
    CHECK_THAT(table.output, Catch::Contains("peak 2"));
}

TEST_CASE("compare: --progress reports each pair of a batch on stderr, stdout unchanged", "[cli][compare]") {
    const fs::path dir = scratch_dir("compare_progress");
    for (int f = 1; f <= 3; ++f) {
        write_flat(dir / ("t." + std::to_string(f) + ".exr"), 0.5f + 0.1f * float(f));
        write_flat(dir / ("r." + std::to_string(f) + ".exr"), 0.5f);
    }
    const std::string seqs = (dir / "t.#.exr").string() + " " + (dir / "r.#.exr").string();
    const SplitRun quiet = run_split("compare " + seqs + " --json", dir);
    const SplitRun progress = run_split("compare " + seqs + " --json --progress", dir);
    REQUIRE(progress.exit_code == 0);
    CHECK(progress.out == quiet.out);
    CHECK(quiet.err.empty());
    CHECK_THAT(progress.err, Catch::Contains("[1/3]") && Catch::Contains("[3/3]") && Catch::Contains("left"));
}
