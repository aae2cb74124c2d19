#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace aaf {

/// The widest x86-64 instruction set that the project's vector kernels
/// (Google Highway) and Embree's traversal kernels may use, process-wide.
///
/// Native, the default, lets each library take the fastest the CPU has.
/// Results are deterministic for one setting on one kind of CPU; across
/// settings the filters differ by rounding (fused multiply-adds exist from
/// AVX2 on), so a farm of mixed CPUs that wants identical bytes from every
/// node pins one set that all of them have (sse4.2 exists on every x86-64
/// CPU in use). The tracer's hit distances and normals do not depend on the
/// setting (libaaf/trace/README.md, "Portable hits").
enum class InstructionSet { Native, Sse42, Avx2, Avx512 };

/// The settings in order, Native first.
inline constexpr InstructionSet kInstructionSets[] = {InstructionSet::Native, InstructionSet::Sse42,
                                                      InstructionSet::Avx2, InstructionSet::Avx512};

/// "native", "sse4.2", "avx2" or "avx512".
const char *instruction_set_name(InstructionSet set);
/// The setting `name` spells (instruction_set_name's spelling), or none.
std::optional<InstructionSet> parse_instruction_set(std::string_view name);
/// The names joined as "native, sse4.2, avx2, avx512", for messages.
std::string instruction_set_choices();
/// Whether this CPU runs `set` (Avx512: F, CD, DQ, BW and VL, as Embree's
/// and Highway's AVX-512 kernels need; Avx2: with FMA).
bool cpu_supports(InstructionSet set);

/// Pins the kernels to at most `set` from now on. Throws aaf::Error naming
/// the set when this CPU does not run it.
void set_instruction_set(InstructionSet set);
/// The pinned set: set_instruction_set's, else $AAF_ISA's on first use
/// (applied then), else Native. Throws aaf::Error naming AAF_ISA when the
/// variable holds no setting or one this CPU cannot run.
InstructionSet instruction_set();

}  // namespace aaf
