#include "provenance.h"

#include <cinttypes>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/io/exr_io.h"

namespace aaf::cli {

namespace {

std::string &stored_command_line() {
    static std::string line;
    return line;
}

/// FNV-1a, 64 bits: a stable hash for identities, not for security.
struct Fnv1a {
    std::uint64_t state = 14695981039346656037ull;
    void add(const void *data, std::size_t size) {
        const auto *bytes = static_cast<const unsigned char *>(data);
        for (std::size_t i = 0; i < size; ++i) state = (state ^ bytes[i]) * 1099511628211ull;
    }
    void add(const std::string &text) { add(text.data(), text.size() + 1); }  // the NUL separates fields
    std::string hex() const {
        char text[17];
        std::snprintf(text, sizeof text, "%016" PRIx64, state);
        return text;
    }
};

const std::string *string_attribute(const AovSet &aovs, const char *name) {
    auto it = aovs.attributes.find(name);
    return it == aovs.attributes.end() ? nullptr : std::get_if<std::string>(&it->second);
}

}  // namespace

const char *aaf_version() {
    return "aaf 0.1.0";
}

void set_command_line(int argc, char **argv) {
    // Left out: what cannot change a frame's bytes by contract (threads,
    // progress, resumption, which chunk of a sequence, where it is written,
    // the memory limit), so equal outputs stay equal bytes; and the
    // instruction set, which changes no render and a filter's last bits only.
    static const std::set<std::string> with_value = {"-o",           "--output",   "--frames",
                                                     "--threads",    "--progress", "--resume",
                                                     "--checkpoint", "--isa",      "--memory-limit-gb"};
    static const std::set<std::string> flags = {"--skip-existing", "--skip-bad-frames", "--timings"};
    std::string &line = stored_command_line();
    line = "aaf";
    for (int i = 1; i < argc; ++i) {
        const std::string word = argv[i];
        const std::string name = word.substr(0, word.find('='));
        if (flags.count(word) || with_value.count(name)) {
            if (name == word && with_value.count(word)) ++i;  // "--threads 2", not "--threads=2"
            continue;
        }
        line += " " + word;
    }
}

const std::string &command_line() {
    return stored_command_line();
}

std::string inputs_hash(const std::vector<std::string> &files, const std::string &extra) {
    namespace fs = std::filesystem;
    Fnv1a hash;
    hash.add(extra);
    for (const std::string &file : files) {
        std::error_code error;
        const auto size = fs::file_size(file, error);
        if (error) {
            hash.add(std::string("missing"));
            continue;
        }
        const auto modified = fs::last_write_time(file, error).time_since_epoch().count();
        hash.add(&size, sizeof size);
        hash.add(&modified, sizeof modified);
        std::ifstream in(file, std::ios::binary);
        std::string head(64 * 1024, '\0');
        in.read(head.data(), std::streamsize(head.size()));
        head.resize(std::size_t(in.gcount()));
        hash.add(head);
    }
    return hash.hex();
}

void stamp(const Provenance &provenance, AovSet &aovs) {
    aovs.attributes["Software"] = std::string(aaf_version());  // not the input's renderer
    aovs.attributes[provenance_attr::kVersion] = std::string(aaf_version());
    aovs.attributes[provenance_attr::kMethod] = provenance.method;
    aovs.attributes[provenance_attr::kParameters] = provenance.parameters;
    aovs.attributes[provenance_attr::kCommand] = command_line();
    aovs.attributes[provenance_attr::kInputsHash] = provenance.inputs_hash;
    if (!provenance.history.empty())
        aovs.attributes[provenance_attr::kHistory] = provenance.history;
    else
        aovs.attributes.erase(provenance_attr::kHistory);  // a filtered input's, not this output's
}

bool output_up_to_date(const std::string &output, const Provenance &expected) {
    if (!io::is_readable_image(output)) return false;  // missing, truncated by a killed run, not an image
    try {
        const AovSet recorded = io::read_aovs(output);
        const auto equals = [&](const char *name, const std::string &value) {
            const std::string *text = string_attribute(recorded, name);
            return text && *text == value;
        };
        if (!equals(provenance_attr::kVersion, aaf_version()) ||
            !equals(provenance_attr::kMethod, expected.method) ||
            !equals(provenance_attr::kParameters, expected.parameters) ||
            !equals(provenance_attr::kInputsHash, expected.inputs_hash))
            return false;
        if (expected.history.empty() ? recorded.attributes.count(provenance_attr::kHistory) != 0
                                     : !equals(provenance_attr::kHistory, expected.history))
            return false;
        if (expected.method != "render") return true;
        // A progressive render's checkpoint holds fewer samples than asked for.
        const auto done = recorded.attributes.find(attr::kSppDone),
                   target = recorded.attributes.find(attr::kSpp);
        if (done == recorded.attributes.end() || target == recorded.attributes.end()) return false;
        const int *done_spp = std::get_if<int>(&done->second),
                  *target_spp = std::get_if<int>(&target->second);
        return done_spp && target_spp && *done_spp >= *target_spp;
    } catch (const std::exception &) {
        return false;
    }
}

}  // namespace aaf::cli
