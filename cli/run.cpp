#include <exception>
#include <iostream>

#include "aaf/core/error.h"
#include "aaf/io/atomic_file.h"
#include "commands.h"

namespace aaf::cli {

int run(int argc, char **argv) {
    CLI::App app{"aaf: image-space reconstruction of ray-traced distribution effects"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "aaf 0.1.0");
    add_render_command(app);
    add_plan_command(app);
    add_filter_command(app);
    add_compare_command(app);
    add_info_command(app);
    add_preview_command(app);
    // Ctrl-C or a farm's SIGTERM leaves no hidden temporary behind (a render
    // installs its own handler: it finishes the round and writes it).
    io::remove_temporaries_on_signal();
    try {
        app.parse(argc, argv);
    } catch (const CheckFailed &) {
        return kExitCheckFailed;
    } catch (const Interrupted &) {
        return kExitInterrupted;
    } catch (const InputError &e) {
        std::cerr << "aaf: error: " << e.what() << "\n";
        return kExitInputError;
    } catch (const UsageError &e) {
        std::cerr << "aaf: error: " << e.what() << "\n";
        return kExitUsage;
    } catch (const CLI::ParseError &e) {
        // Help and version exit 0; usage errors exit 2.
        return app.exit(e) == 0 ? 0 : kExitUsage;
    } catch (const std::exception &e) {
        std::cerr << "aaf: error: " << e.what() << "\n";
        return 1;
    }
    return 0;
}

}  // namespace aaf::cli
