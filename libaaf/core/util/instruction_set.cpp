#include "aaf/core/util/instruction_set.h"

#include <hwy/targets.h>

#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <mutex>

#include "aaf/core/util/error.h"
#include "aaf/core/util/quoted.h"

namespace aaf {

namespace {

std::mutex pin_mutex;
std::atomic<bool> pinned{false};
std::atomic<InstructionSet> current{InstructionSet::Native};

/// Highway's targets better than `set` (a lower bit is a better target).
std::int64_t highway_targets_above(InstructionSet set) {
    switch (set) {
        case InstructionSet::Sse42:
            return HWY_SSE4 - 1;
        case InstructionSet::Avx2:
            return HWY_AVX2 - 1;
        case InstructionSet::Avx512:
            return HWY_AVX3 - 1;
        case InstructionSet::Native:
            break;
    }
    return 0;
}

void apply(InstructionSet set) {
    if (!cpu_supports(set))
        throw Error(std::string("this CPU cannot run instruction set ") + instruction_set_name(set));
    // Also makes Highway choose its dispatch targets again.
    hwy::DisableTargets(highway_targets_above(set));
    current.store(set);
    pinned.store(true);
}

}  // namespace

const char *instruction_set_name(InstructionSet set) {
    switch (set) {
        case InstructionSet::Sse42:
            return "sse4.2";
        case InstructionSet::Avx2:
            return "avx2";
        case InstructionSet::Avx512:
            return "avx512";
        case InstructionSet::Native:
            break;
    }
    return "native";
}

std::optional<InstructionSet> parse_instruction_set(std::string_view name) {
    for (InstructionSet set : kInstructionSets)
        if (name == instruction_set_name(set)) return set;
    return std::nullopt;
}

std::string instruction_set_choices() {
    std::string choices;
    for (InstructionSet set : kInstructionSets)
        choices += (choices.empty() ? "" : ", ") + std::string(instruction_set_name(set));
    return choices;
}

bool cpu_supports(InstructionSet set) {
    switch (set) {
        case InstructionSet::Native:
            return true;
        case InstructionSet::Sse42:
            return __builtin_cpu_supports("sse4.2");
        case InstructionSet::Avx2:
            return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
        case InstructionSet::Avx512:
            return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512cd") &&
                   __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw") &&
                   __builtin_cpu_supports("avx512vl");
    }
    return false;
}

void set_instruction_set(InstructionSet set) {
    const std::lock_guard<std::mutex> lock(pin_mutex);
    apply(set);
}

InstructionSet instruction_set() {
    if (pinned.load()) return current.load();
    const std::lock_guard<std::mutex> lock(pin_mutex);
    if (pinned.load()) return current.load();
    const char *variable = std::getenv("AAF_ISA");
    std::optional<InstructionSet> set = InstructionSet::Native;
    if (variable && *variable) set = parse_instruction_set(variable);
    if (!set)
        throw Error("AAF_ISA=" + quoted(variable) + " names no instruction set (" +
                    instruction_set_choices() + ")");
    try {
        apply(*set);
    } catch (const Error &e) {
        throw Error(std::string("AAF_ISA: ") + e.what());
    }
    return *set;
}

}  // namespace aaf
