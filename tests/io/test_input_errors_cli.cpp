// The damaged-input promises of the io layer, kept through the `aaf` binary:
// exit codes, the single error line naming the file, no output left behind.
#include <catch2/catch.hpp>

#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <string>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/io/exr_io.h"
#include "crafted_exr.h"

#include "../cli/run_aaf.h"

using namespace aaf;
using aaf_test::run_aaf;
using aaf_test::scratch_dir;
namespace fs = std::filesystem;

namespace {

bool is_one_error_line(const std::string &output) {
    return output.rfind("aaf: error: ", 0) == 0 && std::count(output.begin(), output.end(), '\n') == 1;
}

/// Peak resident memory of the largest child run so far, in MB.
double peak_child_mb() {
    rusage usage{};
    getrusage(RUSAGE_CHILDREN, &usage);
    return double(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KB on Linux
}

}  // namespace

TEST_CASE("filter exits 3 naming the file and the attribute for a bad light in the header", "[io][cli]") {
    const fs::path dir = scratch_dir("cli_bad_light");
    const std::string rendered = (dir / "rendered.exr").string();
    REQUIRE(run_aaf("render grids -o " + rendered + " --width 16 --height 12 --spp 2").exit_code == 0);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const std::vector<std::pair<const char *, AttributeValue>> cases = {
        {attr::kLightSigma, 0.0f},           {attr::kLightSigma, nan},
        {attr::kLightNormal, Vec3{0, 0, 0}}, {attr::kLightAxisU, Vec3{nan, 0, 0}},
        {attr::kLightAxisU, Vec3{0, -1, 0}},  // parallel to the grids light's normal
        {attr::kLightWidth, -1.0f},
    };
    for (const auto &[name, value] : cases) {
        AovSet aovs = io::read_aovs(rendered);
        aovs.attributes[name] = value;
        const std::string bad = (dir / "bad.exr").string(), out = (dir / "out.exr").string();
        io::write_aovs(aovs, bad);
        const std::vector<char> before = aaf_test::file_bytes(bad);
        const auto result = run_aaf("filter aaf " + bad + " -o " + out);
        CAPTURE(name, result.output);
        CHECK(result.exit_code == 3);
        CHECK(is_one_error_line(result.output));
        CHECK(result.output.find(bad + ": ") != std::string::npos);
        CHECK(result.output.find(std::string("'") + name + "'") != std::string::npos);
        CHECK(!fs::exists(out));
        CHECK(aaf_test::file_bytes(bad) == before);
    }
    CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 2);  // rendered, bad
}

TEST_CASE("info on a header declaring 100000x100000 exits 3 on the memory limit with little memory",
          "[io][cli][memory]") {
    const fs::path dir = scratch_dir("cli_huge_header");
    const std::string path = (dir / "huge.exr").string();
    aaf_test::write_noise_exr(path, 8, 8, 3);
    aaf_test::declare_size(path, 100000, 100000);
    const auto result = run_aaf("info " + path);
    CHECK(result.exit_code == 3);
    CHECK(is_one_error_line(result.output));
    CHECK(result.output.find(path + ": declares 100000x100000 with 3 channels") != std::string::npos);
    CHECK(result.output.find("AAF_MEMORY_LIMIT_GB") != std::string::npos);
    CHECK(peak_child_mb() < 300);
    // The limit can be raised; then the file's missing chunks are what fails.
    ::setenv("AAF_MEMORY_LIMIT_GB", "200", 1);
    const auto raised = run_aaf("info " + path);
    ::unsetenv("AAF_MEMORY_LIMIT_GB");
    CHECK(raised.exit_code == 3);
    CHECK(raised.output.find("over the memory limit") == std::string::npos);
    CHECK(raised.output.find(path + ": ") != std::string::npos);
    CHECK(peak_child_mb() < 300);
}

TEST_CASE("info on a 60 KB file declaring 8000x8000 exits 3 without allocating the declared size",
          "[io][cli][memory]") {
    const fs::path dir = scratch_dir("cli_small_file_big_header");
    const std::string path = (dir / "small.exr").string();
    aaf_test::write_noise_exr(path, 64, 64, 4);
    aaf_test::declare_size(path, 8000, 8000);
    const auto result = run_aaf("info " + path);
    CAPTURE(result.output);
    CHECK(result.exit_code == 3);
    CHECK(is_one_error_line(result.output));
    CHECK(result.output.find(path + ": ") != std::string::npos);
    CHECK(peak_child_mb() < 300);
}

TEST_CASE("a truncated output frame is redone by --skip-existing", "[io][cli][sequence]") {
    const fs::path dir = scratch_dir("cli_skip_truncated");
    const std::string in = (dir / "in.####.exr").string(), out = (dir / "out.####.exr").string();
    REQUIRE(run_aaf("render grids -o " + in + " --frames 1-2 --width 16 --height 12 --spp 2").exit_code == 0);
    REQUIRE(run_aaf("filter aaf " + in + " -o " + out + " --frames 1-2").exit_code == 0);
    const std::string first = (dir / "out.0001.exr").string(), second = (dir / "out.0002.exr").string();
    const std::vector<char> complete = aaf_test::file_bytes(second), untouched = aaf_test::file_bytes(first);
    aaf_test::truncate_to_half(second);
    REQUIRE(!io::is_readable_image(second));
    const auto result = run_aaf("filter aaf " + in + " -o " + out + " --frames 1-2 --skip-existing");
    CAPTURE(result.output);
    CHECK(result.exit_code == 0);
    CHECK(io::is_readable_image(second));
    CHECK(aaf_test::file_bytes(second) == complete);
    CHECK(aaf_test::file_bytes(first) == untouched);
}

TEST_CASE("an output path that is a folder exits 3 with 'is a directory'", "[io][cli]") {
    const fs::path dir = scratch_dir("cli_folder_output");
    const std::string in = (dir / "in.exr").string();
    const fs::path folder = dir / "out.exr";
    REQUIRE(run_aaf("render grids -o " + in + " --width 16 --height 12 --spp 2").exit_code == 0);
    fs::create_directory(folder);
    const auto result = run_aaf("filter aaf " + in + " -o " + folder.string());
    CHECK(result.exit_code == 3);
    CHECK(result.output == "aaf: error: " + folder.string() + ": is a directory\n");
    CHECK(fs::is_empty(folder));
}

TEST_CASE("an input that is a folder exits 3 with 'is a directory' before any reader tries it", "[io][cli]") {
    // OpenImageIO would try every format reader on a folder; libheif's could run for minutes.
    const fs::path dir = scratch_dir("cli_folder_input");
    const fs::path folder = dir / "in.exr";
    fs::create_directory(folder);
    const std::string expected = "aaf: error: " + folder.string() + ": is a directory, not an image\n";
    const std::string commands[] = {"info " + folder.string(),
                                    "filter aaf " + folder.string() + " -o " + (dir / "out.exr").string()};
    for (const std::string &command : commands) {
        const auto result = run_aaf(command);
        INFO(command);
        CHECK(result.exit_code == 3);
        CHECK(result.output == expected);
    }
    CHECK(fs::is_empty(folder));
    CHECK(!fs::exists(dir / "out.exr"));
}
