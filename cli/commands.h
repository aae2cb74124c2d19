#pragma once

#include <CLI/CLI.hpp>

namespace aaf::cli {

/// Each adds one subcommand (with its options and action) to the `aaf` app.
void add_render_command(CLI::App &app);
void add_filter_command(CLI::App &app);
void add_compare_command(CLI::App &app);
void add_info_command(CLI::App &app);
void add_preview_command(CLI::App &app);
void add_plan_command(CLI::App &app);

}  // namespace aaf::cli
