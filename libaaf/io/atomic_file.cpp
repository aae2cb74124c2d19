#include "aaf/io/atomic_file.h"

#include <atomic>
#include <filesystem>
#include <system_error>

#include <unistd.h>

#include "aaf/core/error.h"

namespace aaf::io {

std::string temporary_path_for(const std::string &path) {
    static std::atomic<unsigned> counter{0};
    std::filesystem::path target(path);
    std::string name = "." + target.filename().string() + ".tmp-" + std::to_string(::getpid()) + "-" +
                       std::to_string(counter++);
    return (target.parent_path() / name).string();
}

void commit_temporary(const std::string &temporary, const std::string &path) {
    std::error_code ec;
    std::filesystem::rename(temporary, path, ec);
    if (ec) {
        std::filesystem::remove(temporary, ec);
        throw InputError(path + ": cannot move the finished file into place: " + ec.message());
    }
}

}  // namespace aaf::io
