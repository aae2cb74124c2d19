#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <sstream>
#include <string>
#include <variant>
#include <vector>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/contract/aov_set.h"
#include "aaf/core/util/instruction_set.h"

/// Byte-level hashes of AOV sets for the golden tests: a failing check
/// prints the new hash; one is updated only when an output is meant to change.
namespace aaf_test {

/// FNV-1a, 64 bits.
class Fnv1a {
  public:
    void add(const void *data, std::size_t size) {
        const auto *bytes = static_cast<const unsigned char *>(data);
        for (std::size_t i = 0; i < size; ++i) hash_ = (hash_ ^ bytes[i]) * 0x100000001b3ull;
    }
    void add(const std::string &text) { add(text.data(), text.size() + 1); }  // with the terminator
    void add(float value) {
        std::uint32_t bits;
        std::memcpy(&bits, &value, sizeof bits);
        add(&bits, sizeof bits);
    }
    void add(int value) { add(&value, sizeof value); }
    void add(std::uint64_t value) { add(&value, sizeof value); }
    std::uint64_t value() const { return hash_; }

  private:
    std::uint64_t hash_ = 0xcbf29ce484222325ull;
};

/// Adds every channel of `aovs` (name, precision, float bits, in order).
inline void add_channels(Fnv1a &hash, const aaf::AovSet &aovs) {
    hash.add(aovs.width());
    hash.add(aovs.height());
    for (std::size_t c = 0; c < aovs.channel_names().size(); ++c) {
        hash.add(aovs.channel_names()[c]);
        hash.add(int(aovs.precision(c)));
        for (float value : aovs.plane(c)) hash.add(value);
    }
}

/// Hash of every channel and every attribute. The scene file's path depends
/// on the checkout, so only its file name counts.
inline std::uint64_t golden_hash(const aaf::AovSet &aovs) {
    Fnv1a hash;
    add_channels(hash, aovs);
    for (const auto &attribute : aovs.attributes) {
        hash.add(attribute.first);
        const aaf::AttributeValue &value = attribute.second;
        hash.add(int(value.index()));
        if (const int *i = std::get_if<int>(&value)) hash.add(*i);
        if (const float *f = std::get_if<float>(&value)) hash.add(*f);
        if (const aaf::Vec3 *v = std::get_if<aaf::Vec3>(&value)) {
            hash.add(v->x);
            hash.add(v->y);
            hash.add(v->z);
        }
        if (const std::string *s = std::get_if<std::string>(&value))
            hash.add(attribute.first == aaf::attr::kSceneFile ? std::filesystem::path(*s).filename().string()
                                                              : *s);
    }
    return hash.value();
}

inline std::string hex(std::uint64_t value) {
    std::ostringstream out;
    out << "0x" << std::hex << std::setw(16) << std::setfill('0') << value;
    return out.str();
}

/// Every pinned instruction set this CPU runs (sse4.2 on every x86-64
/// machine, then avx2 and avx512 where present).
inline std::vector<aaf::InstructionSet> instruction_sets_here() {
    std::vector<aaf::InstructionSet> sets;
    for (aaf::InstructionSet set : aaf::kInstructionSets)
        if (set != aaf::InstructionSet::Native && aaf::cpu_supports(set)) sets.push_back(set);
    return sets;
}

/// The fraction of a render's values that may differ between instruction
/// sets: a ray through an edge two triangles share may find the other
/// triangle under another set of Embree's kernels.
inline constexpr double kEdgeGrazingFraction = 1e-3;

/// How far `test` is from `reference`: the largest difference of any channel
/// value relative to max(1, |reference|), and the fraction of values that
/// differ by more than `tolerance` in that measure (NaN against NaN agrees;
/// differing channel names or plane sizes count as every value beyond).
struct Agreement {
    double largest = 0;
    double fraction_beyond = 0;
};

inline Agreement agreement(const aaf::AovSet &reference, const aaf::AovSet &test, double tolerance) {
    Agreement result;
    if (reference.channel_names() != test.channel_names()) return {INFINITY, 1.0};
    std::size_t beyond = 0, values = 0;
    for (std::size_t c = 0; c < reference.channel_names().size(); ++c) {
        const aaf::AovSet::Plane &a = reference.plane(c), &b = test.plane(c);
        if (a.size() != b.size()) return {INFINITY, 1.0};
        for (std::size_t i = 0; i < a.size(); ++i, ++values) {
            if (std::isnan(a[i]) && std::isnan(b[i])) continue;
            const double difference =
                std::abs(double(a[i]) - double(b[i])) / std::max(1.0, std::abs(double(a[i])));
            if (!(difference <= tolerance)) ++beyond;  // NaN against a number counts too
            if (!(difference <= result.largest))
                result.largest = std::isnan(difference) ? INFINITY : difference;
        }
    }
    result.fraction_beyond = double(beyond) / double(std::max<std::size_t>(values, 1));
    return result;
}

}  // namespace aaf_test
