// The MAAF study (Wu et al. 2017, Sec. 6.1 and Fig. 12): on grids and
// tentacles, RMSE of the beauty against a converged reference for MAAF at a
// few spp, and for AAF with adaptive sampling and its filter (the AAF study's
// "AS+AF": first pass 9 spp, mu swept); wall-clock seconds split into
// sampling, MAAF's accumulation (the maaf group: keeping the samples, the
// wedges and the 50 sums) and filtering. Writes one CSV row per run; run
// through ./scripts/maaf_study.sh, which plots it and interpolates AAF's
// measured curve at MAAF's errors and times.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <vector>

#include "aaf/core/framework/filter_aovs.h"
#include "aaf/core/framework/method_registry.h"
#include "aaf/core/kernels/sample_statistics.h"
#include "aaf/core/methods/aaf/aaf_filter.h"
#include "aaf/core/metrics/error_metrics.h"
#include "aaf/core/util/error.h"
#include "aaf/io/atomic_file.h"
#include "aaf/trace/render.h"

namespace {

using namespace aaf;
using Clock = std::chrono::steady_clock;

const std::vector<std::string> kRgb{"R", "G", "B"};

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

struct Row {
    std::string scene, method;
    double setting, avg_spp, rmse, sampling_s, accumulation_s, filter_s;
};

}  // namespace

int main(int argc, char **argv) {
    CLI::App app{"MAAF study: RMSE and time of MAAF against AAF with adaptive sampling"};
    std::vector<std::string> scenes{"grids", "tentacles"};
    std::string output = "maaf_study.csv";
    int width = 320, height = 240, reference_spp = 4096;
    std::vector<int> maaf_spp{4, 9, 16, 25, 64};
    // The CLI default width scale first, then the paper's reading (MaafParams::k).
    std::vector<std::string> maaf_k{"3", "1"};
    std::vector<float> mu_values{0.5f, 0.75f, 1.0f, 1.5f, 2.0f, 3.0f, 4.0f, 6.0f};
    app.add_option("--scenes", scenes, "Built-in scenes")->delimiter(',')->capture_default_str();
    app.add_option("-o,--output", output, "CSV path")->capture_default_str();
    app.add_option("--width", width)->capture_default_str();
    app.add_option("--height", height)->capture_default_str();
    app.add_option("--reference-spp", reference_spp)->capture_default_str();
    app.add_option("--maaf-spp", maaf_spp, "MAAF spp values")->delimiter(',')->capture_default_str();
    app.add_option("--maaf-k", maaf_k, "MAAF width scales k (the first is reported as MAAF)")
        ->delimiter(',')
        ->capture_default_str();
    app.add_option("--mu", mu_values, "AAF adaptive-sampling mu values")
        ->delimiter(',')
        ->capture_default_str();
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
            const trace::AovGroups aaf_groups = trace::aov_groups_for_method("aaf");
            for (int spp : maaf_spp) {
                settings.spp = spp;
                settings.aovs = aaf_groups;  // the same rays without MAAF's group: sampling alone
                auto start = Clock::now();
                (void)trace::render_scene(scene, settings);
                const double sampling_s = seconds_since(start);
                settings.aovs = trace::aov_groups_for_method("maaf");
                start = Clock::now();
                const AovSet noisy = trace::render_scene(scene, settings);
                const double with_maaf_s = seconds_since(start);
                const Method &maaf = find_method("maaf");
                for (const std::string &k : maaf_k) {
                    ParameterSet parameters = maaf.default_parameters();
                    parameters.set("k", k);
                    start = Clock::now();
                    const AovSet filtered = filter_aovs(maaf, noisy, ChannelMap{}, parameters);
                    const double filter_s = seconds_since(start);
                    const std::string name = k == maaf_k.front() ? "MAAF" : "MAAF k=" + k;
                    rows.push_back({scene, name, double(spp), double(spp),
                                    compare_channels(filtered, reference, kRgb).rmse, sampling_s,
                                    std::max(0.0, with_maaf_s - sampling_s), filter_s});
                    std::fprintf(
                        stderr,
                        "%-10s %s %3d spp: RMSE %.5f  sampling %.2f s  accumulation %.2f s  filter %.2f s\n",
                        scene.c_str(), name.c_str(), spp, rows.back().rmse, sampling_s,
                        rows.back().accumulation_s, filter_s);
                }
            }
            settings.aovs = aaf_groups;
            settings.spp = 9;  // AAF Sec. 6: the first pass
            settings.adaptive = true;
            settings.max_spp = 1000;
            for (float mu : mu_values) {
                settings.plan.mu = mu;
                auto start = Clock::now();
                const AovSet noisy = trace::render_scene(scene, settings);
                const double sampling_s = seconds_since(start);
                AafParams params;
                params.mu = mu;
                params.mu_from_spp = true;  // AAF Sec. 5.2: the filter follows the samples taken
                start = Clock::now();
                const AovSet filtered = aaf_filter_aovs(noisy, ChannelMap{}, params);
                const double filter_s = seconds_since(start);
                const double spp =
                    mean_spp_over_shaded(noisy.channel("pixel.spp"), noisy.channel("id.object"));
                rows.push_back({scene, "AAF-AS", double(mu), spp,
                                compare_channels(filtered, reference, kRgb).rmse, sampling_s, 0.0, filter_s});
                std::fprintf(
                    stderr,
                    "%-10s AAF adaptive mu %.2f: avg %.1f spp  RMSE %.5f  sampling %.2f s  filter %.2f s\n",
                    scene.c_str(), mu, spp, rows.back().rmse, sampling_s, filter_s);
            }
        }
        const std::string temporary = io::temporary_path_for(output);
        {
            std::ofstream csv(temporary);
            csv << "scene,method,setting,avg_spp,rmse,sampling_s,accumulation_s,filter_s\n";
            for (const Row &r : rows)
                csv << r.scene << ',' << r.method << ',' << r.setting << ',' << r.avg_spp << ',' << r.rmse
                    << ',' << r.sampling_s << ',' << r.accumulation_s << ',' << r.filter_s << '\n';
            if (!csv) throw Error(output + ": cannot write");
        }
        io::commit_temporary(temporary, output);
    } catch (const std::exception &e) {
        std::cerr << "maaf_study: error: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
