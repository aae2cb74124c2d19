#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "aaf/core/error.h"
#include "aaf/core/error_metrics.h"
#include "aaf/io/exr_io.h"
#include "commands.h"

namespace aaf::cli {

void add_compare_command(CLI::App &app) {
    struct Options {
        std::string test, reference;
        std::vector<std::string> channels{"R", "G", "B"};
        bool json = false;
    };
    auto options = std::make_shared<Options>();
    CLI::App *cmd = app.add_subcommand("compare", "Error of an image against a reference (RMSE, MSE, PSNR)");
    cmd->add_option("test", options->test, "Image to measure")->required();
    cmd->add_option("reference", options->reference, "Reference image")->required();
    cmd->add_option("--channels", options->channels, "Channels to compare")
        ->delimiter(',')
        ->capture_default_str();
    cmd->add_flag("--json", options->json, "Print one JSON object");
    cmd->callback([options] {
        AovSet test = io::read_aovs(options->test);
        AovSet reference = io::read_aovs(options->reference);
        ErrorMetrics metrics;
        try {
            metrics = compare_channels(test, reference, options->channels);
        } catch (const Error &e) {
            throw Error(options->test + " vs " + options->reference + ": " + e.what());
        }
        if (options->json) {
            nlohmann::json out = {{"test", options->test},
                                  {"reference", options->reference},
                                  {"channels", options->channels},
                                  {"rmse", metrics.rmse},
                                  {"mse", metrics.mse}};
            // JSON has no infinity: identical images report a null PSNR.
            out["psnr"] = std::isfinite(metrics.psnr) ? nlohmann::json(metrics.psnr) : nlohmann::json();
            std::cout << out.dump() << "\n";
        } else {
            std::printf("RMSE %.6g  MSE %.6g  PSNR %.3f dB\n", metrics.rmse, metrics.mse, metrics.psnr);
        }
    });
}

}  // namespace aaf::cli
