#pragma once

#include <CLI/CLI.hpp>

#include "aaf/core/util/error.h"

namespace aaf::cli {

/// A command line that cannot mean anything (a bad frame range or progress
/// mode, patterns that do not pair up); `aaf` exits with kExitUsage, as for
/// CLI11's own parse errors (and for the library's aaf::ParameterError).
class UsageError : public ParameterError {
  public:
    explicit UsageError(const std::string &message) : ParameterError(message) {}
};
inline constexpr int kExitUsage = 2;
/// Thrown by a command that ran to the end but whose check failed
/// (`aaf compare --fail-above`); `aaf` exits with kExitCheckFailed.
struct CheckFailed {};
inline constexpr int kExitCheckFailed = 4;
/// Exit code for aaf::InputError: unreadable, unwritable or incomplete files.
inline constexpr int kExitInputError = 3;
/// Thrown when an interrupt (Ctrl-C, SIGTERM) stopped a render after it had
/// written what it had, resumable; `aaf` exits with kExitInterrupted (128 + SIGINT).
struct Interrupted {};
inline constexpr int kExitInterrupted = 130;

/// The `aaf` tool: parses `argv`, runs the subcommand, maps errors to the
/// exit codes above (printing `aaf: error: <problem>`). Every method
/// registered when it runs (method_registry.h) gets its `aaf filter` subcommand.
int run(int argc, char **argv);

/// Each adds one subcommand (with its options and action) to the `aaf` app.
void add_render_command(CLI::App &app);
void add_filter_command(CLI::App &app);
void add_compare_command(CLI::App &app);
void add_info_command(CLI::App &app);
void add_preview_command(CLI::App &app);
void add_plan_command(CLI::App &app);
void add_analyze_command(CLI::App &app);

}  // namespace aaf::cli
