#pragma once

#include "aaf/core/util/instruction_set.h"

namespace aaf_test {

/// Lifts the process's instruction-set pin (AAF_ISA, --isa) for a test that
/// walks every Highway target itself (hwy::SetSupportedTargetsForTest does
/// not reach targets a pin disabled), and restores it afterwards.
class UnpinnedInstructionSet {
  public:
    UnpinnedInstructionSet() : before_(aaf::instruction_set()) {
        aaf::set_instruction_set(aaf::InstructionSet::Native);
    }
    ~UnpinnedInstructionSet() { aaf::set_instruction_set(before_); }
    UnpinnedInstructionSet(const UnpinnedInstructionSet &) = delete;
    UnpinnedInstructionSet &operator=(const UnpinnedInstructionSet &) = delete;

  private:
    aaf::InstructionSet before_;
};

}  // namespace aaf_test
