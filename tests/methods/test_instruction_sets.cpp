// The same renders and filters under every instruction set this CPU runs
// (instruction_set.h): sse4.2, which every x86-64 CPU has, is the
// reference, and avx2 and avx512, where present, must agree with it up to
// rounding. A kernel that is wrong on one instruction set only (a Highway
// target's lane handling, an Embree kernel's hit) shows up on any machine
// that has two of them.
#include <tbb/global_control.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "../golden_hash.h"
#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/framework/filter_aovs.h"
#include "aaf/core/framework/method_registry.h"
#include "aaf/core/util/instruction_set.h"
#include "aaf/trace/render.h"

using namespace aaf;
using aaf_test::Agreement;
using aaf_test::agreement;

namespace {

/// Pins `set` for the guard's life, then restores the process's setting.
class PinnedInstructionSet {
  public:
    explicit PinnedInstructionSet(InstructionSet set) : before_(instruction_set()) {
        set_instruction_set(set);
    }
    ~PinnedInstructionSet() { set_instruction_set(before_); }
    PinnedInstructionSet(const PinnedInstructionSet &) = delete;
    PinnedInstructionSet &operator=(const PinnedInstructionSet &) = delete;

  private:
    InstructionSet before_;
};

/// The sets compared with sse4.2: every other pinned set this CPU runs.
std::vector<InstructionSet> wider_sets_here() {
    std::vector<InstructionSet> sets;
    for (InstructionSet set : {InstructionSet::Avx2, InstructionSet::Avx512})
        if (cpu_supports(set)) sets.push_back(set);
    return sets;
}

/// Every AOV group the tracer writes (kAovsAll leaves out the method-specific passes).
const trace::AovGroups kEveryGroup = trace::parse_aov_groups("all,maaf,isg,maaf6");

AovSet render(const std::string &scene, InstructionSet set) {
    const PinnedInstructionSet pin(set);
    trace::RenderSettings settings;
    settings.width = 32;
    settings.height = 24;
    settings.spp = 4;
    settings.seed = 3;
    settings.aovs = kEveryGroup;
    return trace::render_scene(scene, settings);
}

}  // namespace

TEST_CASE("Every instruction set renders the shipped scenes to the same AOVs", "[isa][trace]") {
    if (wider_sets_here().empty()) WARN("this CPU runs sse4.2 only: nothing to compare it with");
    // Embree finds the triangle and the tracer computes the hit itself, so
    // the bytes agree exactly; a ray that grazes a shared edge may still find
    // the neighbouring triangle under another set, hence at most 0.1% of the
    // values may differ, each by any amount.
    for (const char *scene : {"grids", "studio", "room", "livingroom", "gallery"}) {
        const AovSet reference = render(scene, InstructionSet::Sse42);
        for (InstructionSet set : wider_sets_here()) {
            const Agreement a = agreement(reference, render(scene, set), 0.0);
            INFO("scene " << scene << ", " << instruction_set_name(set)
                          << " against sse4.2: largest relative " << a.largest
                          << ", fraction of values that differ " << a.fraction_beyond);
            CHECK(a.fraction_beyond <= aaf_test::kEdgeGrazingFraction);
        }
    }
}

TEST_CASE("Every method filters alike under every instruction set, up to rounding", "[isa][methods]") {
    if (wider_sets_here().empty()) WARN("this CPU runs sse4.2 only: nothing to compare it with");
    const tbb::global_control allow(tbb::global_control::max_allowed_parallelism, 4);
    AovSet input = render("grids", InstructionSet::Sse42);
    for (const RoleInfo &role : role_table())  // roles no group writes, for a future method's own AOVs
        for (const std::string &name : role.channels)
            if (!input.has_channel(name)) input.add_channel(name, 0.5f);
    for (const Method *method : methods()) {
        const auto run = [&](InstructionSet set) {
            const PinnedInstructionSet pin(set);
            return filter_aovs(*method, input, ChannelMap{}, method->default_parameters());
        };
        const AovSet reference = run(InstructionSet::Sse42);
        for (InstructionSet set : wider_sets_here()) {
            // Fused multiply-adds (avx2 and wider) round once where sse4.2
            // rounds twice: the weights, and so the outputs, differ in the
            // last bits only.
            const Agreement a = agreement(reference, run(set), 1e-5);
            INFO("method " << method->info().name << ", " << instruction_set_name(set)
                           << " against sse4.2: largest relative " << a.largest << ", fraction beyond 1e-5 "
                           << a.fraction_beyond);
            CHECK(a.fraction_beyond == 0);
        }
    }
}
