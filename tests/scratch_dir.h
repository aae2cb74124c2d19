#pragma once

#include <filesystem>
#include <string>

namespace aaf_test {

/// A fresh, empty directory under the test build tree.
inline std::filesystem::path scratch_dir(const std::string &name) {
    std::filesystem::path dir = std::filesystem::path(AAF_TEST_BINARY_DIR) / "scratch" / name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

}  // namespace aaf_test
