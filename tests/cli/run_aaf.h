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

/// Runs the aaf executable with `args` (a progressive render with
/// `--checkpoint` and `-o output`), sends it SIGINT (Ctrl-C) as soon as its
/// first checkpoint is on disk (its handler is set long before) and returns
/// its exit code (that of its own end if it ends before any checkpoint). `scratch` holds the exit code's
/// file.
inline int interrupt_at_first_checkpoint(const std::string &args, const fs::path &output,
                                         const fs::path &scratch) {
    const fs::path rc_path = scratch / "interrupt_rc.txt";
    fs::remove(rc_path);
    const std::string script = "(" + std::string(AAF_EXECUTABLE) + " " + args +
                               " >/dev/null 2>&1 & pid=$!; while [ ! -f " + output.string() +
                               " ] && kill -0 $pid 2>/dev/null; do sleep 0.02; done; kill -INT $pid; "
                               "wait $pid; echo $? > " +
                               rc_path.string() + ")";
    if (std::system(("/bin/sh -c '" + script + "'").c_str()) != 0) return -1;
    std::ifstream rc_file(rc_path);
    int rc = -1;
    rc_file >> rc;
    return rc;
}

}  // namespace aaf_test
