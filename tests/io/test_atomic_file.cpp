#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "aaf/core/util/error.h"
#include "aaf/io/atomic_file.h"
#include "aaf/io/exr_io.h"

#include "../scratch_dir.h"

using namespace aaf;
using aaf_test::scratch_dir;
namespace fs = std::filesystem;

namespace {

AovSet small_image() {
    AovSet aovs(4, 3);
    aovs.add_channel("R", 0.5f);
    return aovs;
}

void touch(const fs::path &path) {
    std::ofstream(path) << "not ours to delete";
}

/// The name of the temporary this process would use for `output`, up to
/// its "PID-N" end.
std::string temporary_prefix(const fs::path &output) {
    const std::string temporary = io::temporary_path_for(output.string());
    io::discard_temporary(temporary);
    const std::string name = fs::path(temporary).filename().string();
    return name.substr(0, name.find(".tmp-") + 5);
}

}  // namespace

TEST_CASE("a write removes the temporaries a killed run left for the same output, and nothing else",
          "[io][atomic]") {
    const fs::path dir = scratch_dir("atomic_leftovers");
    const fs::path output = dir / "out.exr";
    // pid 999999999 is above Linux's largest pid_max (4194304): a gone process.
    const fs::path leftover = dir / ".out.exr.tmp-999999999-0";
    const std::string live = std::to_string(::getppid());  // a running process: a writer still at work
    const std::vector<fs::path> foreign = {
        dir / ".out.exr.tmp-999999999-0.keep", dir / ".out.exr.tmp-abc-1",
        dir / ".out.exr.tmp-999999999",        dir / ".other.exr.tmp-999999999-0",
        dir / "out.exr.tmp-999999999-0",       dir / (".out.exr.tmp-" + live + "-0"),
        dir / ".out.exr.tmp-999999999-0-1",
    };
    touch(leftover);
    for (const fs::path &path : foreign) touch(path);
    io::write_aovs(small_image(), output.string());
    CHECK(fs::exists(output));
    CHECK(!fs::exists(leftover));
    for (const fs::path &path : foreign) {
        CAPTURE(path);
        CHECK(fs::exists(path));
    }
}

TEST_CASE("an output name of 250 characters is written, its temporary within 255 bytes", "[io][atomic]") {
    const fs::path dir = scratch_dir("atomic_long_name");
    const fs::path output = dir / (std::string(246, 'n') + ".exr");
    REQUIRE(output.filename().string().size() == 250);
    const std::string prefix = temporary_prefix(output);
    CHECK(prefix.size() + 21 <= 255);           // room for "PID-N" of 10 digits each
    CHECK(prefix == temporary_prefix(output));  // the same name every run, so leftovers are found
    const fs::path leftover = dir / (prefix + "999999999-3");
    touch(leftover);
    io::write_aovs(small_image(), output.string());
    CHECK(io::is_readable_image(output.string()));
    CHECK(!fs::exists(leftover));
    CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 1);
}

TEST_CASE("writing into a missing folder gives the system's reason under the output's name", "[io][atomic]") {
    const fs::path dir = scratch_dir("atomic_missing_folder");
    const std::string output = (dir / "missing" / "out.exr").string();
    try {
        io::write_aovs(small_image(), output);
        FAIL("wrote into a missing folder");
    } catch (const aaf::InputError &e) {
        CHECK(std::string(e.what()) == output + ": cannot write: No such file or directory");
    }
    CHECK(fs::is_empty(dir));
}

TEST_CASE("a leftover of an earlier process with this process's pid is removed, a live temporary kept",
          "[io][atomic]") {
    const fs::path dir = scratch_dir("atomic_reused_pid");
    const fs::path output = dir / "out.exr";
    const std::string live = io::temporary_path_for(output.string());  // this process, still writing
    const fs::path reused = dir / (".out.exr.tmp-" + std::to_string(::getpid()) + "-999999");
    touch(reused);
    io::write_aovs(small_image(), output.string());
    CHECK(!fs::exists(reused));
    CHECK(fs::exists(live));
    io::discard_temporary(live);
    CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 1);
}
