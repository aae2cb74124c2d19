#pragma once

#include <CLI/CLI.hpp>

namespace aaf::cli {

/// Thrown by a command that ran to the end but whose check failed
/// (`aaf compare --fail-above`); `aaf` exits with kExitCheckFailed.
struct CheckFailed {};
inline constexpr int kExitCheckFailed = 4;  // 3 is kept for input/IO errors (issue 5)

/// Each adds one subcommand (with its options and action) to the `aaf` app.
void add_render_command(CLI::App &app);
void add_filter_command(CLI::App &app);
void add_compare_command(CLI::App &app);
void add_info_command(CLI::App &app);
void add_preview_command(CLI::App &app);
void add_plan_command(CLI::App &app);

}  // namespace aaf::cli
