// Golden hashes of every method's output on every shipped scene, taken
// before the methods' inputs, parameters and folders were restructured: the
// filtered channels (name, precision, float bits) and attributes of
// `filter_aovs` at each method's defaults, and of `aaf filter` as a file,
// must stay byte-identical through such refactors. A failing check prints
// the new hashes; update one only when an output is meant to change.
//
// Neither the tracer's bytes (the golden renders) nor the filters' depend
// on the instruction set: every kernel rounds each multiply and add on its
// own, so one hash per method holds under sse4.2, avx2 and avx512.
#include <catch2/catch.hpp>

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "../cli/run_aaf.h"
#include "../golden_hash.h"
#include "aaf/core/framework/filter_aovs.h"
#include "aaf/core/framework/method_registry.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/instruction_set.h"
#include "aaf/io/exr_io.h"
#include "aaf/trace/render.h"

using namespace aaf;
using aaf_test::Fnv1a;
using aaf_test::hex;

namespace {

struct Golden {
    const char *method;
    std::uint64_t hash;       ///< filter_aovs on every scene
    std::uint64_t file_hash;  ///< aaf filter's file of grids
};

const Golden kGolden[] = {
    {"aaf", 0xe8df97acd8a0b47d, 0x0a7832d26da9720c},
    {"gaussian", 0xa205a6afb5c4ff8a, 0xe563c08506aa4719},
    {"maaf", 0x8325c4b7bcded58b, 0x23bfd07e4743f5a5},
    {"isg-shadow", 0x2f9d9752e62f3cb2, 0x09c7ab2e67b66445},
    {"isg-glossy", 0xdaa05b40f82737f8, 0xe47911939bb27072},
    {"isg-dof", 0xdbd25054dd127f2c, 0x9819c505026c321b},
    {"ratio", 0x0d8844afe2599350, 0x715ff6b08e944c32},
    {"maaf6", 0x3164412da8c0bc21, 0xc7b360f0c80a8218},
};

/// The render a method's own `--aovs METHOD` makes of `scene`, small.
trace::RenderSettings settings_for(const std::string &method) {
    trace::RenderSettings settings;
    settings.width = 32;
    settings.height = 24;
    settings.spp = 4;
    settings.seed = 7;
    settings.threads = 2;
    settings.aovs = trace::aov_groups_for_method(method);
    return settings;
}

/// Hash of `method` at its defaults over every shipped scene: each scene's
/// output (or, where the method refuses the render, its message) in turn.
std::uint64_t method_hash(const Method &method, std::map<std::string, AovSet> &renders) {
    Fnv1a hash;
    int filtered = 0;
    for (const std::string &scene : trace::builtin_scene_names()) {
        const trace::RenderSettings settings = settings_for(method.info().name);
        const std::string key = scene + "/" + settings.aovs.text();
        if (!renders.count(key)) renders.emplace(key, trace::render_scene(scene, settings));
        hash.add(scene);
        try {
            hash.add(aaf_test::golden_hash(
                filter_aovs(method, renders.at(key), ChannelMap{}, method.default_parameters())));
            ++filtered;
        } catch (const Error &error) {
            hash.add(std::string("refused: ") + error.what());
        }
    }
    CHECK(filtered > 0);  // a method that refuses every render would check nothing
    return hash.value();
}

}  // namespace

TEST_CASE("Every method filters every shipped scene to the golden bytes", "[methods][golden]") {
    std::map<std::string, AovSet> renders;  // the tracer's bytes are the same under every set
    const InstructionSet before = instruction_set();
    for (const Golden &golden : kGolden) {
        const Method &method = find_method(golden.method);
        for (InstructionSet set : aaf_test::instruction_sets_here()) {
            set_instruction_set(set);
            const std::uint64_t hash = method_hash(method, renders);
            INFO("method " << golden.method << ", instruction set " << instruction_set_name(set) << ": hash "
                           << hex(hash) << ", golden " << hex(golden.hash));
            CHECK(hash == golden.hash);
        }
    }
    set_instruction_set(before);
}

TEST_CASE("aaf filter writes every method's golden channels as a file", "[methods][golden][cli]") {
    namespace fs = std::filesystem;
    const fs::path dir = aaf_test::scratch_dir("filter_golden");
    // Run under the process's own instruction set (AAF_ISA under scripts/test_isa.sh).
    for (const Golden &golden : kGolden) {
        INFO("method " << golden.method);
        const fs::path input = dir / (std::string(golden.method) + ".in.exr");
        const fs::path output = dir / (std::string(golden.method) + ".out.exr");
        REQUIRE(
            aaf_test::run_aaf("render grids --width 32 --height 24 --spp 4 --seed 7 --progress none --aovs " +
                              std::string(golden.method) + " -o " + input.string())
                .exit_code == 0);
        const auto filtered = aaf_test::run_aaf("filter " + std::string(golden.method) + " " +
                                                input.string() + " --progress none -o " + output.string());
        REQUIRE(filtered.exit_code == 0);
        Fnv1a hash;
        aaf_test::add_channels(hash, io::read_aovs(output.string()));
        INFO("file hash " << hex(hash.value()));
        CHECK(hash.value() == golden.file_hash);
    }
}
