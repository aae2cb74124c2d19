#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

namespace aaf::fuzz {

/// A file in $TMPDIR (or /tmp) holding one fuzz input, removed again when this
/// goes out of scope: the readers under test take paths, not memory. The name
/// carries the process id, so harnesses running side by side (and libFuzzer's
/// fork-mode children) never share a file.
class TempFile {
  public:
    TempFile(const std::string &suffix, const std::uint8_t *data, std::size_t size) {
        const char *tmp = std::getenv("TMPDIR");
        path_ = std::string(tmp ? tmp : "/tmp") + "/aaf_fuzz_" + std::to_string(::getpid()) + suffix;
        std::ofstream(path_, std::ios::binary | std::ios::trunc)
            .write(reinterpret_cast<const char *>(data), static_cast<std::streamsize>(size));
    }
    ~TempFile() {
        std::error_code ignored;
        std::filesystem::remove(path_, ignored);
    }
    TempFile(const TempFile &) = delete;
    TempFile &operator=(const TempFile &) = delete;

    const std::string &path() const { return path_; }

  private:
    std::string path_;
};

}  // namespace aaf::fuzz
