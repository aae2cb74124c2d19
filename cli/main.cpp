#include <exception>
#include <iostream>

#include "aaf/core/error.h"
#include "aaf/io/atomic_file.h"
#include "commands.h"

int main(int argc, char **argv) {
    CLI::App app{"aaf: image-space reconstruction of ray-traced distribution effects"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "aaf 0.1.0");
    aaf::cli::add_render_command(app);
    aaf::cli::add_plan_command(app);
    aaf::cli::add_filter_command(app);
    aaf::cli::add_compare_command(app);
    aaf::cli::add_info_command(app);
    aaf::cli::add_preview_command(app);
    // Ctrl-C or a farm's SIGTERM leaves no hidden temporary behind (a render
    // installs its own handler: it finishes the round and writes it).
    aaf::io::remove_temporaries_on_signal();
    try {
        app.parse(argc, argv);
    } catch (const aaf::cli::CheckFailed &) {
        return aaf::cli::kExitCheckFailed;
    } catch (const aaf::cli::Interrupted &) {
        return aaf::cli::kExitInterrupted;
    } catch (const aaf::InputError &e) {
        std::cerr << "aaf: error: " << e.what() << "\n";
        return aaf::cli::kExitInputError;
    } catch (const aaf::cli::UsageError &e) {
        std::cerr << "aaf: error: " << e.what() << "\n";
        return aaf::cli::kExitUsage;
    } catch (const CLI::ParseError &e) {
        // Help and version exit 0; usage errors exit 2.
        return app.exit(e) == 0 ? 0 : aaf::cli::kExitUsage;
    } catch (const std::exception &e) {
        std::cerr << "aaf: error: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
