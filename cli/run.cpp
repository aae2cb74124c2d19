#include <cstdint>
#include <cstdio>
#include <exception>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "aaf/core/util/error.h"
#include "aaf/core/util/instruction_set.h"
#include "aaf/io/atomic_file.h"
#include "aaf/io/exr_io.h"
#include "commands.h"
#include "provenance.h"
#include "suggestion.h"

namespace aaf::cli {

namespace {

/// `message` on one line: line breaks (a library's multi-line text) become
/// "; ", other control characters (raw bytes in a channel name) \xNN.
std::string one_line(const std::string &message) {
    std::string line;
    for (std::size_t i = 0; i < message.size(); ++i) {
        const auto byte = static_cast<unsigned char>(message[i]);
        if (byte == '\n' || byte == '\r') {
            if (i + 1 < message.size() && message[i + 1] != '\n' && message[i + 1] != '\r') line += "; ";
        } else if (byte < 0x20 || byte == 0x7f) {
            char escaped[8];
            std::snprintf(escaped, sizeof escaped, "\\x%02x", byte);
            line += escaped;
        } else {
            line += message[i];
        }
    }
    return line;
}

/// Prints the one line of an error, `aaf: error: <message>`, and returns `code`.
int report(const std::string &message, int code) {
    std::cerr << "aaf: error: " << one_line(message) << "\n";
    return code;
}

/// Throws UsageError naming an unknown subcommand and the one meant: CLI11
/// would only say "A subcommand is required" for `aaf frobnicate` or `aaf
/// filter nosuch`.
void check_subcommand_names(const CLI::App &app, int argc, char **argv) {
    const CLI::App *level = &app;
    for (int i = 1; i < argc && level->get_require_subcommand_min() > 0; ++i) {
        const std::string word = argv[i];
        if (word.empty() || word[0] == '-') return;  // an option: CLI11 reports what is wrong with it
        std::string known;
        std::vector<std::string> names;
        const CLI::App *next = nullptr;
        for (const CLI::App *sub : level->get_subcommands([](const CLI::App *) { return true; })) {
            known += (known.empty() ? "" : ", ") + sub->get_name();
            names.push_back(sub->get_name());
            if (sub->get_name() == word) next = sub;
        }
        if (!next) {
            const char *what = level == &app                   ? "command"
                               : level->get_name() == "filter" ? "method"
                                                               : "subcommand";
            throw UsageError(std::string("unknown ") + what + " '" + word + "' (" + known + ")" +
                             did_you_mean(word, names));
        }
        level = next;
    }
}

/// "; did you mean '--x'?" for the first unexpected argument that is a
/// misspelt option of the subcommand given (or of a command above it, whose
/// options it accepts too), else "". CLI11 itself only lists what it did not expect.
std::string option_suggestion(const CLI::App &app) {
    const CLI::App *level = &app;
    for (std::vector<CLI::App *> parsed = level->get_subcommands(); !parsed.empty();
         parsed = level->get_subcommands())
        level = parsed.front();
    std::vector<std::string> names;
    for (const CLI::App *owner = level; owner != nullptr; owner = owner->get_parent())
        for (const CLI::Option *option : owner->get_options())
            for (const std::string &name : option->get_lnames()) names.push_back("--" + name);
    for (const std::string &argument : app.remaining(/*recurse=*/true)) {
        if (argument.rfind("--", 0) != 0) continue;
        const std::string hint = did_you_mean(argument.substr(0, argument.find('=')), names);
        if (!hint.empty()) return hint;
    }
    return {};
}

}  // namespace

int run(int argc, char **argv) {
    CLI::App app{"aaf: image-space reconstruction of ray-traced distribution effects"};
    app.require_subcommand(1);
    app.set_version_flag("--version", aaf_version());
    set_command_line(argc, argv);
    // Accepted before or after the subcommand (fallthrough): every command reads images.
    app.fallthrough();
    app.add_option_function<double>(
           "--memory-limit-gb",
           [](double gib) { io::set_memory_budget_bytes(std::uint64_t(gib * 1024.0 * 1024.0 * 1024.0)); },
           "Largest image (all channels, as float) a command may read, GiB; default 16 or "
           "$AAF_MEMORY_LIMIT_GB")
        ->check(CLI::Range(1.0e-6, 1.0e6));
    app.add_option_function<std::string>(
        "--isa",
        [](const std::string &name) {
            const std::optional<InstructionSet> set = parse_instruction_set(name);
            if (!set)
                throw UsageError("--isa: unknown instruction set '" + name + "' (" +
                                 instruction_set_choices() + ")");
            if (!cpu_supports(*set)) throw UsageError("--isa " + name + ": this CPU cannot run it");
            set_instruction_set(*set);
        },
        "Widest instruction set of the filter kernels and Embree: native (the fastest this CPU runs), "
        "sse4.2, avx2 or avx512; default native or $AAF_ISA. Pin one that every node has for identical "
        "bytes across a farm of mixed CPUs");
    add_render_command(app);
    add_plan_command(app);
    add_filter_command(app);
    add_compare_command(app);
    add_info_command(app);
    add_preview_command(app);
    add_analyze_command(app);
    // Ctrl-C or a farm's SIGTERM leaves no hidden temporary behind (a render
    // installs its own handler: it finishes the round and writes it).
    io::remove_temporaries_on_signal();
    try {
        try {
            (void)instruction_set();  // a wrong $AAF_ISA is a usage error, named before any work
        } catch (const Error &e) {
            throw UsageError(e.what());
        }
        check_subcommand_names(app, argc, argv);
        app.parse(argc, argv);
    } catch (const CheckFailed &) {
        return kExitCheckFailed;
    } catch (const Interrupted &) {
        return kExitInterrupted;
    } catch (const InputError &e) {
        return report(e.what(), kExitInputError);
    } catch (const ParameterError &e) {  // UsageError among them
        return report(e.what(), kExitUsage);
    } catch (const CLI::ExtrasError &e) {
        return report(e.what() + option_suggestion(app), kExitUsage);
    } catch (const CLI::ParseError &e) {
        // --help and --version print as CLI11 prints them and exit 0; a parse
        // error is one line, like every other error, and exits 2.
        if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);
        return report(e.what(), kExitUsage);
    } catch (const std::exception &e) {
        return report(e.what(), 1);
    }
    return 0;
}

}  // namespace aaf::cli
