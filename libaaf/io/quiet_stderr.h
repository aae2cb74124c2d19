#pragma once

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>

namespace aaf::io {

/// True when `path` starts with the PNG signature, whatever its name.
inline bool has_png_signature(const std::string &path) {
    char bytes[8] = {};
    std::ifstream file(path, std::ios::binary);
    return file.read(bytes, sizeof bytes) && std::string(bytes, 8) == "\x89PNG\r\n\x1a\n";
}

/// While alive (and `active`), the process's stderr goes to /dev/null: libpng
/// prints "libpng error: ..." itself before OpenImageIO's PNG reader reports
/// the same problem through its error API, which the caller turns into the
/// one error line. Used only around reading a PNG, on the calling thread.
class QuietStderr {
  public:
    explicit QuietStderr(bool active) {
        if (!active) return;
        std::fflush(stderr);
        saved_ = ::dup(STDERR_FILENO);
        const int null = ::open("/dev/null", O_WRONLY);
        if (saved_ < 0 || null < 0 || ::dup2(null, STDERR_FILENO) < 0) restore();
        if (null >= 0) ::close(null);
    }
    ~QuietStderr() { restore(); }
    QuietStderr(const QuietStderr &) = delete;
    QuietStderr &operator=(const QuietStderr &) = delete;

  private:
    void restore() {
        if (saved_ < 0) return;
        std::fflush(stderr);
        ::dup2(saved_, STDERR_FILENO);
        ::close(saved_);
        saved_ = -1;
    }
    int saved_ = -1;
};

}  // namespace aaf::io
