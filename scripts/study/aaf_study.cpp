// The study of AAF Fig. 6(c): RMSE against a converged reference versus the
// average samples per pixel, for {non-adaptive (NAS), adaptive (AS) sampling}
// x {unfiltered (UF), fixed-width Gaussian (NAF), adaptive filter (AF)}.
// Writes one CSV row per (scene, sampling, filter, setting). Run through
// ./scripts/study.sh, which also plots the CSV.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <limits>
#include <vector>

#include "aaf/core/aaf_filter.h"
#include "aaf/core/error.h"
#include "aaf/core/error_metrics.h"
#include "aaf/core/sample_statistics.h"
#include "aaf/io/atomic_file.h"
#include "aaf/trace/render.h"

namespace {

using namespace aaf;

const std::vector<std::string> kRgb{"R", "G", "B"};

/// The non-adaptive filter (NAF): AAF's gather with one world-space beta for
/// every pixel, the width that best matches the reference (an oracle choice,
/// as the paper's "chosen to best match the final image").
std::pair<double, float> best_fixed_filter(const AovSet &noisy, const AovSet &reference) {
    double best_rmse = std::numeric_limits<double>::infinity();
    float best_beta = 0;
    for (float beta_m : {0.0025f, 0.005f, 0.01f, 0.015f, 0.02f, 0.03f, 0.045f, 0.065f, 0.09f}) {
        AafParams params;
        params.fixed_beta_m = beta_m;
        const double rmse =
            compare_channels(aaf_filter_aovs(noisy, ChannelMap{}, params), reference, kRgb).rmse;
        if (rmse < best_rmse) {
            best_rmse = rmse;
            best_beta = beta_m;
        }
    }
    return {best_rmse, best_beta};
}

struct Row {
    std::string scene, sampling, filter;
    double setting, avg_spp, rmse, fixed_beta_m;
};

void evaluate(const std::string &scene, const std::string &sampling, double setting, const AovSet &noisy,
              const AovSet &reference, float filter_mu, std::vector<Row> &rows) {
    const double spp = mean_spp_over_shaded(noisy.channel("pixel.spp"), noisy.channel("id.object"));
    rows.push_back({scene, sampling, "UF", setting, spp, compare_channels(noisy, reference, kRgb).rmse, 0});
    const auto [fixed_rmse, beta_m] = best_fixed_filter(noisy, reference);
    rows.push_back({scene, sampling, "NAF", setting, spp, fixed_rmse, beta_m});
    AafParams params;
    params.mu = filter_mu;
    params.mu_from_spp = true;  // Sec. 5.2: the filter follows the samples taken
    const AovSet filtered = aaf_filter_aovs(noisy, ChannelMap{}, params);
    rows.push_back(
        {scene, sampling, "AF", setting, spp, compare_channels(filtered, reference, kRgb).rmse, 0});
    const Row &last = rows.back();
    std::fprintf(stderr, "%-10s %s mu/spp %-6g avg spp %7.2f  UF %.5f  NAF %.5f (beta %.4f m)  AF %.5f\n",
                 scene.c_str(), sampling.c_str(), setting, spp, rows[rows.size() - 3].rmse, fixed_rmse,
                 beta_m, last.rmse);
}

}  // namespace

int main(int argc, char **argv) {
    CLI::App app{"AAF study: RMSE vs average spp (AAF Fig. 6(c))"};
    std::vector<std::string> scenes{"grids", "tentacles"};
    std::string output = "study.csv";
    int width = 320, height = 240, reference_spp = 4096;
    std::vector<int> spp_values{9, 16, 25, 36, 64, 100, 150, 225};
    std::vector<float> mu_values{1.0f, 1.5f, 2.0f, 3.0f, 4.0f, 6.0f};
    app.add_option("--scenes", scenes, "Built-in scenes")->delimiter(',')->capture_default_str();
    app.add_option("-o,--output", output, "CSV path")->capture_default_str();
    app.add_option("--width", width)->capture_default_str();
    app.add_option("--height", height)->capture_default_str();
    app.add_option("--reference-spp", reference_spp)->capture_default_str();
    app.add_option("--spp", spp_values, "Non-adaptive spp values")->delimiter(',')->capture_default_str();
    app.add_option("--mu", mu_values, "Adaptive-sampling mu values")->delimiter(',')->capture_default_str();
    CLI11_PARSE(app, argc, argv);

    try {
        std::vector<Row> rows;
        for (const std::string &scene : scenes) {
            trace::RenderSettings settings;
            settings.width = width;
            settings.height = height;
            settings.spp = reference_spp;
            settings.seed = 1000;  // independent of the test renders
            const AovSet reference = trace::render_scene(scene, settings);
            settings.seed = 1;
            for (int spp : spp_values) {
                settings.spp = spp;
                evaluate(scene, "NAS", spp, trace::render_scene(scene, settings), reference, 2.0f, rows);
            }
            settings.spp = 9;  // AAF Sec. 6: the first pass
            settings.adaptive = true;
            settings.max_spp = 1000;
            for (float mu : mu_values) {
                settings.adaptive_mu = mu;
                evaluate(scene, "AS", mu, trace::render_scene(scene, settings), reference, mu, rows);
            }
        }
        const std::string temporary = io::temporary_path_for(output);
        {
            std::ofstream csv(temporary);
            csv << "scene,sampling,filter,setting,avg_spp,rmse,fixed_beta_m\n";
            for (const Row &r : rows)
                csv << r.scene << ',' << r.sampling << ',' << r.filter << ',' << r.setting << ',' << r.avg_spp
                    << ',' << r.rmse << ',' << r.fixed_beta_m << '\n';
            if (!csv) throw Error(output + ": cannot write");
        }
        io::commit_temporary(temporary, output);
    } catch (const std::exception &e) {
        std::cerr << "aaf_study: error: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
