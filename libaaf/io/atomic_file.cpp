#include "aaf/io/atomic_file.h"

#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <system_error>
#include <thread>

#include <fcntl.h>
#include <signal.h>
#include <sys/types.h>
#include <unistd.h>

#include "aaf/core/util/error.h"

namespace aaf::io {

namespace {

/// Temporaries not yet committed, readable from a signal handler: fixed
/// slots, each claimed (kFilling), filled, then published (kLive).
enum SlotState : int { kFree, kFilling, kLive };
struct TemporarySlot {
    std::atomic<int> state{kFree};
    char path[4096];
};
constexpr int kSlots = 64;  // files one process writes at once, with room to spare
TemporarySlot g_slots[kSlots];
std::atomic<unsigned> g_next_slot{0};

void remember(const std::string &path) {
    if (path.size() >= sizeof(TemporarySlot::path)) return;  // written, but not removable on a signal
    for (int tries = 0; tries < kSlots; ++tries) {
        TemporarySlot &slot = g_slots[g_next_slot++ % kSlots];
        int expected = kFree;
        if (slot.state.compare_exchange_strong(expected, kFilling)) {
            std::memcpy(slot.path, path.c_str(), path.size() + 1);
            slot.state.store(kLive);
            return;
        }
    }
}

void forget(const std::string &path) {
    for (TemporarySlot &slot : g_slots) {
        int expected = kLive;
        if (slot.state.load() == kLive && path == slot.path)
            slot.state.compare_exchange_strong(expected, kFree);
    }
}

extern "C" void remove_temporaries_and_reraise(int signal) {
    for (TemporarySlot &slot : g_slots)
        if (slot.state.load() == kLive) ::unlink(slot.path);  // async-signal-safe
    std::signal(signal, SIG_DFL);
    std::raise(signal);
}

/// The part of a temporary's name before "PID-N": ".NAME.tmp-", or, when
/// that would push the name past the 255 bytes most file systems allow, the
/// first bytes of NAME with a hash of the whole name instead of NAME.
std::string temporary_prefix(const std::string &filename) {
    constexpr std::size_t kMaxKept = 180;  // + "~" + 16 hex + ".tmp-PID-N" (<= 26) stays under 255
    if (filename.size() <= kMaxKept + 17) return "." + filename + ".tmp-";
    std::uint64_t hash = 14695981039346656037ull;  // FNV-1a, 64 bit
    for (const char c : filename) hash = (hash ^ static_cast<unsigned char>(c)) * 1099511628211ull;
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(hash));
    return "." + filename.substr(0, kMaxKept) + "~" + hex + ".tmp-";
}

bool is_live_here(const std::string &path) {
    for (const TemporarySlot &slot : g_slots)
        if (slot.state.load() == kLive && path == slot.path) return true;
    return false;
}

/// True when `rest` is "PID-N" (decimal digits only) and PID names no
/// running process, or this process (a reused pid) but not one of its own
/// unfinished temporaries: a temporary left by a killed run.
bool is_abandoned(const std::string &path, const std::string &rest) {
    const std::size_t dash = rest.find('-');
    auto digits = [](const std::string &text) {
        return !text.empty() && text.size() <= 10 &&
               text.find_first_not_of("0123456789") == std::string::npos;
    };
    if (dash == std::string::npos || !digits(rest.substr(0, dash)) || !digits(rest.substr(dash + 1)))
        return false;
    const long long pid = std::stoll(rest.substr(0, dash));
    if (pid <= 0 || pid > std::numeric_limits<pid_t>::max()) return false;
    if (pid == ::getpid()) return !is_live_here(path);
    return ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;  // EPERM: alive, another user's
}

/// Removes the temporaries of `target` that a killed run of this tool left
/// (SIGKILL cannot be caught): regular files named exactly `prefix`PID-N
/// whose process is gone. Anything else, another program's files included,
/// stays; failures are ignored (the new write does not depend on them).
void remove_abandoned_temporaries(const std::filesystem::path &target, const std::string &prefix) {
    std::error_code ec;
    const std::filesystem::path directory = target.has_parent_path() ? target.parent_path() : ".";
    for (std::filesystem::directory_iterator it(directory, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
        std::error_code type_ec;
        if (!it->is_regular_file(type_ec) || it->is_symlink(type_ec)) continue;
        // Spelled as temporary_path_for() spells (and remembers) its temporaries.
        if (is_abandoned((target.parent_path() / name).string(), name.substr(prefix.size())))
            std::filesystem::remove(it->path(), type_ec);
    }
}

}  // namespace

void check_not_same_file(const std::string &input, const std::string &output) {
    std::error_code ec;
    if (std::filesystem::exists(output, ec) && std::filesystem::equivalent(input, output, ec))
        throw InputError(output + ": output would overwrite the input");
}

std::string temporary_path_for(const std::string &path) {
    static std::atomic<unsigned> counter{0};
    std::filesystem::path target(path);
    std::error_code ec;
    if (std::filesystem::is_directory(target, ec)) throw InputError(path + ": is a directory");
    const std::string prefix = temporary_prefix(target.filename().string());
    remove_abandoned_temporaries(target, prefix);
    const std::string name = prefix + std::to_string(::getpid()) + "-" + std::to_string(counter++);
    const std::string temporary = (target.parent_path() / name).string();
    remember(temporary);
    // Created here, so that a directory that is missing or not writable is
    // reported with the system's reason under the output's name.
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0) {
        const std::error_code error(errno, std::generic_category());
        forget(temporary);
        throw InputError(path + ": cannot write: " + error.message());
    }
    ::close(fd);
    return temporary;
}

void commit_temporary(const std::string &temporary, const std::string &path) {
    // Test hook: hold the finished temporary before the rename, so a test can
    // interrupt a run at the moment a partial file would be most exposed.
    if (const char *hold = std::getenv("AAF_TEST_HOLD_BEFORE_RENAME_S"))
        std::this_thread::sleep_for(std::chrono::duration<double>(std::atof(hold)));
    std::error_code ec;
    std::filesystem::rename(temporary, path, ec);
    forget(temporary);
    if (ec) {
        std::filesystem::remove(temporary, ec);
        throw InputError(path + ": cannot move the finished file into place: " + ec.message());
    }
}

void discard_temporary(const std::string &temporary) {
    std::error_code ec;
    std::filesystem::remove(temporary, ec);
    forget(temporary);
}

void remove_temporaries_on_signal() {
    std::signal(SIGINT, remove_temporaries_and_reraise);
    std::signal(SIGTERM, remove_temporaries_and_reraise);
}

}  // namespace aaf::io
