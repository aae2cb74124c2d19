#include "aaf/io/atomic_file.h"

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <system_error>
#include <thread>

#include <unistd.h>

#include "aaf/core/error.h"

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

}  // namespace

void check_not_same_file(const std::string &input, const std::string &output) {
    std::error_code ec;
    if (std::filesystem::exists(output, ec) && std::filesystem::equivalent(input, output, ec))
        throw InputError(output + ": output would overwrite the input");
}

std::string temporary_path_for(const std::string &path) {
    static std::atomic<unsigned> counter{0};
    std::filesystem::path target(path);
    std::string name = "." + target.filename().string() + ".tmp-" + std::to_string(::getpid()) + "-" +
                       std::to_string(counter++);
    const std::string temporary = (target.parent_path() / name).string();
    remember(temporary);
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
