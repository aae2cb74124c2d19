// The study of AAF Fig. 6(c): RMSE against a converged reference versus the
// average samples per pixel, for {non-adaptive (NAS), adaptive (AS) sampling}
// x {unfiltered (UF), fixed-width Gaussian (NAF), adaptive filter (AF)}, with
// the CLI defaults (`aaf render --adaptive`, `aaf filter aaf`), plus on the
// same adaptive render: a sweep of a fixed mu, each departure from the paper
// switched back one at a time, and the paper's whole pipeline (its plan and
// filter settings). Writes one CSV row per (scene, sampling, filter,
// setting). Run through ./scripts/study.sh, which also plots the CSV and
// prints the tables (plot_study.py).
#include <CLI/CLI.hpp>

#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <vector>

#include "aaf/core/kernels/sample_statistics.h"
#include "aaf/core/methods/aaf/aaf_filter.h"
#include "aaf/core/metrics/error_metrics.h"
#include "aaf/core/util/error.h"
#include "aaf/io/atomic_file.h"
#include "aaf/io/exr_io.h"
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

/// The paper's reading where this implementation departs from it (libaaf/core/methods/aaf/README.md): one mu
/// everywhere, AAF Eq. 12's orthogonal projection, one-sided windows at the image edge (Omega_L = 1/sigma and
/// the receiver's pixel footprint are the defaults too).
AafParams paper_params(float mu) {
    AafParams p;
    p.mu = mu;
    p.fixed_mu = true;
    p.light_bandlimit = LightBandlimit::Sigma;
    p.light_distance = AafLightDistance::OrthogonalProjection;
    p.projected_pixel = false;
    p.symmetric_borders = false;
    return p;
}

/// The reference render of `scene` under `settings`, from `cache_dir` when
/// it holds one of that size, spp and seed (a file `aaf render SCENE --spp N
/// --seed 1000` writes too), else rendered, and written there when
/// `cache_dir` is set.
AovSet cached_reference(const std::string &cache_dir, const std::string &scene,
                        const trace::RenderSettings &settings) {
    if (cache_dir.empty()) return trace::render_scene(scene, settings);
    const std::string path = cache_dir + "/" + scene + "_" + std::to_string(settings.width) + "x" +
                             std::to_string(settings.height) + "_" + std::to_string(settings.spp) +
                             "spp_seed" + std::to_string(settings.seed) + ".exr";
    if (std::ifstream(path).good()) {
        AovSet cached = io::read_aovs(path);
        if (cached.width() == settings.width && cached.height() == settings.height) return cached;
    }
    AovSet reference = trace::render_scene(scene, settings);
    io::write_aovs(reference, path);
    return reference;
}

struct Row {
    std::string scene, sampling, filter;
    double setting, avg_spp, rmse, fixed_beta_m;
    /// AF rows: the share of shaded pixels filtered (beta > 0) and their mean beta in pixels.
    double filtered_share = 0, mean_beta_px = 0;
};

/// Over shaded pixels: the share with beta > 0 and the mean of beta / pixel.size over those.
std::pair<double, double> beta_statistics(const AovSet &filtered) {
    const ConstPlaneView beta = filtered.channel("aaf_beta.X"), size = filtered.channel("pixel.size"),
                         id = filtered.channel("id.object");
    double sum = 0;
    long shaded = 0, filtered_count = 0;
    for (int y = 0; y < beta.height; ++y)
        for (int x = 0; x < beta.width; ++x) {
            if (id(x, y) == 0) continue;
            ++shaded;
            if (beta(x, y) > 0 && size(x, y) > 0) {
                ++filtered_count;
                sum += beta(x, y) / size(x, y);
            }
        }
    return {shaded ? double(filtered_count) / double(shaded) : 0.0,
            filtered_count ? sum / double(filtered_count) : 0.0};
}

struct Study {
    std::vector<Row> rows;
    const AovSet *reference = nullptr;
    std::string scene;

    double spp(const AovSet &noisy) const {
        return mean_spp_over_shaded(noisy.channel("pixel.spp"), noisy.channel("id.object"));
    }
    double rmse(const AovSet &image) const { return compare_channels(image, *reference, kRgb).rmse; }
    void add(const std::string &sampling, const std::string &filter, double setting, const AovSet &noisy,
             const AafParams &params) {
        const AovSet filtered = aaf_filter_aovs(noisy, ChannelMap{}, params);
        const auto [share, beta_px] = beta_statistics(filtered);
        rows.push_back({scene, sampling, filter, setting, spp(noisy), rmse(filtered), 0, share, beta_px});
    }
    void add_unfiltered(const std::string &sampling, double setting, const AovSet &noisy) {
        rows.push_back({scene, sampling, "UF", setting, spp(noisy), rmse(noisy), 0});
    }
    void add_fixed(const std::string &sampling, double setting, const AovSet &noisy) {
        const auto [fixed_rmse, beta_m] = best_fixed_filter(noisy, *reference);
        rows.push_back({scene, sampling, "NAF", setting, spp(noisy), fixed_rmse, beta_m});
    }
};

}  // namespace

int main(int argc, char **argv) {
    CLI::App app{"AAF study: RMSE vs average spp (AAF Fig. 6(c)) with the CLI defaults"};
    std::vector<std::string> scenes{"grids", "tentacles", "spheres", "tilted", "grazing", "contact"};
    std::string output = "study.csv";
    int width = 320, height = 240, reference_spp = 4096, max_spp = trace::RenderSettings{}.max_spp;
    std::vector<int> spp_values{9, 16, 25, 36, 64, 100, 150, 225, 400, 625};
    std::vector<float> mu_values{1.0f, 1.5f, 2.0f, 3.0f, 4.0f, 6.0f, 8.0f};
    app.add_option("--scenes", scenes, "Built-in scenes")->delimiter(',')->capture_default_str();
    app.add_option("-o,--output", output, "CSV path")->capture_default_str();
    app.add_option("--width", width)->capture_default_str();
    app.add_option("--height", height)->capture_default_str();
    app.add_option("--reference-spp", reference_spp)->capture_default_str();
    app.add_option("--max-spp", max_spp, "Adaptive cap (the CLI default)")->capture_default_str();
    app.add_option("--spp", spp_values, "Non-adaptive spp values (the plain-MC curve)")
        ->delimiter(',')
        ->capture_default_str();
    app.add_option("--mu", mu_values, "Fixed-mu sweep of the filter on the adaptive render")
        ->delimiter(',')
        ->capture_default_str();
    std::string reference_cache;
    app.add_option("--reference-cache", reference_cache,
                   "Folder of the converged references, <scene>_<W>x<H>_<spp>spp_seed1000.exr: read when "
                   "there, else rendered and written there (empty it after changing the tracer)");
    bool plain_naf = true;
    app.add_flag("!--no-plain-naf", plain_naf,
                 "Skip the oracle fixed-width filter on the plain renders (faster)");
    CLI11_PARSE(app, argc, argv);

    try {
        Study study;
        for (const std::string &scene : scenes) {
            study.scene = scene;
            trace::RenderSettings settings;
            settings.width = width;
            settings.height = height;
            settings.spp = reference_spp;
            settings.seed = 1000;  // independent of the test renders
            const AovSet reference = cached_reference(reference_cache, scene, settings);
            study.reference = &reference;
            settings.seed = 1;
            for (int spp : spp_values) {
                settings.spp = spp;
                const AovSet noisy = trace::render_scene(scene, settings);
                study.add_unfiltered("NAS", spp, noisy);
                if (plain_naf) study.add_fixed("NAS", spp, noisy);
                study.add("NAS", "AF", spp, noisy, AafParams{});
            }
            // The CLI defaults: `aaf render --adaptive` (9 spp first pass, mu 2, the
            // default cap) and `aaf filter aaf`.
            const std::size_t adaptive_rows = study.rows.size();
            settings.spp = 9;
            settings.adaptive = true;
            settings.max_spp = max_spp;
            const AovSet adaptive = trace::render_scene(scene, settings);
            const double default_mu = AafParams{}.mu;
            study.add_unfiltered("AS", default_mu, adaptive);
            study.add_fixed("AS", default_mu, adaptive);
            study.add("AS", "AF", default_mu, adaptive, AafParams{});
            for (float mu : mu_values) {
                AafParams fixed;
                fixed.mu = mu;
                fixed.fixed_mu = true;
                study.add("AS", "AF_fixed_mu", mu, adaptive, fixed);
            }
            // Each departure from the paper switched back alone, and the alternatives not taken.
            const std::pair<const char *, std::function<void(AafParams &)>> ablations[] = {
                {"AF_fixed_mu_default", [](AafParams &p) { p.fixed_mu = true; }},
                {"AF_bandlimit_equivalent_width",
                 [](AafParams &p) { p.light_bandlimit = LightBandlimit::EquivalentWidth; }},
                {"AF_bandlimit_spectrum", [](AafParams &p) { p.light_bandlimit = LightBandlimit::Spectrum; }},
                {"AF_light_axes_shortest", [](AafParams &p) { p.light_axes = AafLightAxes::Shortest; }},
                {"AF_distance_guarded", [](AafParams &p) { p.light_distance = AafLightDistance::Guarded; }},
                {"AF_distance_plane",
                 [](AafParams &p) { p.light_distance = AafLightDistance::OrthogonalProjection; }},
                {"AF_pixel_projected", [](AafParams &p) { p.projected_pixel = true; }},
                {"AF_borders_clip", [](AafParams &p) { p.symmetric_borders = false; }},
            };
            for (const auto &ablation : ablations) {
                AafParams p;
                ablation.second(p);
                study.add("AS", ablation.first, default_mu, adaptive, p);
            }
            // Self-occluded samples skipped (no occluder distance) alone: their effect
            // on the plan's n (avg spp), on beta and on the filter.
            settings.skip_self_occluded = true;
            const AovSet skipped = trace::render_scene(scene, settings);
            settings.skip_self_occluded = false;
            study.add_unfiltered("AS_skip_self_occluded", default_mu, skipped);
            study.add("AS_skip_self_occluded", "AF", default_mu, skipped, AafParams{});
            // The paper's pipeline: its plan (Omega_L = 1/sigma, the receiver's footprint:
            // the defaults' plan too) and its filter settings.
            settings.plan.light_bandlimit = LightBandlimit::Sigma;
            settings.plan.projected_pixel = false;
            const AovSet paper = trace::render_scene(scene, settings);
            settings.plan.light_bandlimit = trace::RenderSettings{}.plan.light_bandlimit;
            settings.plan.projected_pixel = trace::RenderSettings{}.plan.projected_pixel;
            study.add_unfiltered("AS_paper", default_mu, paper);
            study.add("AS_paper", "AF_paper", default_mu, paper, paper_params(float(default_mu)));
            study.add("AS_paper", "AF", default_mu, paper, AafParams{});
            // The same render with this implementation's tracer, filtered as the paper.
            study.add("AS", "AF_paper", default_mu, adaptive, paper_params(float(default_mu)));

            for (std::size_t i = adaptive_rows; i < study.rows.size(); ++i) {
                const Row &r = study.rows[i];
                std::fprintf(stderr,
                             "%-10s %-16s %-30s %-5g avg spp %7.2f  RMSE %.5f  filtered %.3f beta %.2f px\n",
                             r.scene.c_str(), r.sampling.c_str(), r.filter.c_str(), r.setting, r.avg_spp,
                             r.rmse, r.filtered_share, r.mean_beta_px);
            }
        }
        const std::string temporary = io::temporary_path_for(output);
        {
            std::ofstream csv(temporary);
            csv << "scene,sampling,filter,setting,avg_spp,rmse,fixed_beta_m,filtered_share,mean_beta_px\n";
            for (const Row &r : study.rows)
                csv << r.scene << ',' << r.sampling << ',' << r.filter << ',' << r.setting << ',' << r.avg_spp
                    << ',' << r.rmse << ',' << r.fixed_beta_m << ',' << r.filtered_share << ','
                    << r.mean_beta_px << '\n';
            if (!csv) throw Error(output + ": cannot write");
        }
        io::commit_temporary(temporary, output);
    } catch (const std::exception &e) {
        std::cerr << "aaf_study: error: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
