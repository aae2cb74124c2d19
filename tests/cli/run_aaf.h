#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include "../scratch_dir.h"

/// Helpers for tests that run the `aaf` executable.
namespace aaf_test {

namespace fs = std::filesystem;

struct RunResult {
    int exit_code;
    std::string output;  // stdout and stderr
};

/// Runs the aaf executable (or another build of the same front end) with
/// `args` (a shell-quoted string).
inline RunResult run_aaf(const std::string &args, const std::string &executable = AAF_EXECUTABLE) {
    // ctest runs test cases as parallel processes: one log per process and call.
    static int call = 0;
    const fs::path log = fs::path(AAF_TEST_BINARY_DIR) / "scratch" /
                         ("cli_output_" + std::to_string(::getpid()) + "_" + std::to_string(call++) + ".txt");
    fs::create_directories(log.parent_path());
    const std::string command = executable + " " + args + " >" + log.string() + " 2>&1";
    const int status = std::system(command.c_str());
    std::stringstream text;
    text << std::ifstream(log).rdbuf();
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text.str()};
}

}  // namespace aaf_test
