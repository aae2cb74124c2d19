// MAAF for combined effects (Wu et al. 2017, Sec. 6.2, Fig. 12/14) on `room`:
// RMSE against a converged reference for MAAF (N = 3, 25 filters in 6D) and
// for the axis-aligned baseline (the same renders filtered with --pairs 1,
// MYRD14's single filter per layer) over a range of spp; timings split into
// sampling (the maaf6 group's path tracing), pre-filtering (slopes and the
// 6D accumulation) and filtering; the RMSE of the focal-plane pixels that got
// extra samples against their neighbours'. Writes a CSV and the images the
// pictures are drawn from (scripts/plot_maaf6_study.py).
#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <variant>
#include <vector>

#include "aaf/core/framework/filter_aovs.h"
#include "aaf/core/framework/method_registry.h"
#include "aaf/core/util/error.h"
#include "aaf/io/atomic_file.h"
#include "aaf/io/exr_io.h"
#include "aaf/trace/render.h"

using namespace aaf;

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

/// Squared error of R, G, B summed over the pixels where `mask(x, y)` holds, and their count.
template <typename Mask>
std::pair<double, long> squared_error(const AovSet &a, const AovSet &b, const Mask &mask) {
    double sum = 0;
    long count = 0;
    for (const char *name : {"R", "G", "B"}) {
        const ConstPlaneView va = a.channel(name), vb = b.channel(name);
        for (int y = 0; y < a.height(); ++y)
            for (int x = 0; x < a.width(); ++x) {
                if (!mask(x, y)) continue;
                sum += double(va(x, y) - vb(x, y)) * double(va(x, y) - vb(x, y));
                ++count;
            }
    }
    return {sum, count};
}

/// The named channels of `aovs` alone, for the small EXRs the pictures are drawn from.
AovSet only(const AovSet &aovs, const std::vector<std::string> &names) {
    AovSet out(aovs.width(), aovs.height());
    for (const std::string &name : names) {
        const PlaneView to = out.add_channel(name);
        const ConstPlaneView from = aovs.channel(name);
        for (int y = 0; y < aovs.height(); ++y)
            for (int x = 0; x < aovs.width(); ++x) to(x, y) = from(x, y);
    }
    return out;
}

const std::vector<std::string> kRgb{"R", "G", "B"};

double rmse(const AovSet &a, const AovSet &b) {
    const auto [sum, count] = squared_error(a, b, [](int, int) { return true; });
    return std::sqrt(sum / double(count));
}

struct Row {
    std::string method;
    int spp;
    double mean_spp, rmse, sampling_s, prefilter_s, filter_s, focal_rmse, neighbour_rmse;
};

}  // namespace

int main(int argc, char **argv) {
    CLI::App app{"MAAF 6D study on room: MAAF against the axis-aligned baseline"};
    std::string out_dir = ".";
    int width = 320, height = 240, reference_spp = 1024;
    std::vector<int> spp_values{8, 16, 24, 32, 48, 64, 96, 128, 192, 256};
    app.add_option("-o,--out", out_dir, "Output folder (CSV and EXRs)")->capture_default_str();
    app.add_option("--width", width)->capture_default_str();
    app.add_option("--height", height)->capture_default_str();
    app.add_option("--reference-spp", reference_spp)->capture_default_str();
    app.add_option("--spp", spp_values, "spp of the renders both filters run on")
        ->delimiter(',')
        ->capture_default_str();
    CLI11_PARSE(app, argc, argv);
    try {
        trace::RenderSettings settings;
        settings.width = width;
        settings.height = height;
        settings.aovs = trace::parse_aov_groups("maaf6");
        settings.spp = reference_spp;
        settings.seed = 1000;  // independent of the test renders
        const AovSet reference = trace::render_scene("room", settings);
        io::write_aovs(only(reference, kRgb), out_dir + "/reference.exr");
        const Method &method = find_method("maaf6");
        std::vector<Row> rows;
        settings.seed = 1;
        for (int spp : spp_values) {
            settings.spp = spp;
            trace::RenderTimings timings;
            const AovSet noisy = trace::render_scene("room", settings, &timings);
            const ConstPlaneView samples = noisy.channel("maaf6.spp"), id = noisy.channel("id.object");
            double spp_sum = 0;
            for (int y = 0; y < height; ++y)
                for (int x = 0; x < width; ++x) spp_sum += samples(x, y);
            // The focal-plane pixels (extra samples) and their neighbours within 3 px.
            auto focal = [&](int x, int y) { return samples(x, y) > float(spp); };
            auto neighbour = [&](int x, int y) {
                if (focal(x, y) || id(x, y) == 0) return false;
                for (int dy = -3; dy <= 3; ++dy)
                    for (int dx = -3; dx <= 3; ++dx) {
                        const int tx = x + dx, ty = y + dy;
                        if (tx >= 0 && ty >= 0 && tx < width && ty < height && focal(tx, ty)) return true;
                    }
                return false;
            };
            io::write_aovs(only(noisy, {"R", "G", "B", "maaf6.spp"}),
                           out_dir + "/noisy_" + std::to_string(spp) + ".exr");
            for (const char *pairs : {"all", "1"}) {
                ParameterSet parameters = method.default_parameters();
                parameters.set("pairs", std::string(pairs));
                const auto start = Clock::now();
                const AovSet filtered = filter_aovs(method, noisy, ChannelMap{}, parameters);
                const double filter_s = seconds_since(start);
                const bool maaf = std::string(pairs) == "all";
                const auto [focal_sum, focal_count] = squared_error(filtered, reference, focal);
                const auto [near_sum, near_count] = squared_error(filtered, reference, neighbour);
                rows.push_back({maaf ? "MAAF" : "AAF", spp, spp_sum / (double(width) * height),
                                rmse(filtered, reference), timings.maaf6_sampling_s,
                                maaf ? timings.maaf6_prefilter_s : 0.0, filter_s,
                                focal_count ? std::sqrt(focal_sum / double(focal_count)) : 0.0,
                                near_count ? std::sqrt(near_sum / double(near_count)) : 0.0});
                const Row &r = rows.back();
                std::fprintf(
                    stderr,
                    "%-4s %3d spp (mean %.1f): RMSE %.5f  sampling %.2f s  prefilter %.2f s  filter %.2f s  "
                    "focal %.5f  neighbours %.5f\n",
                    r.method.c_str(), spp, r.mean_spp, r.rmse, r.sampling_s, r.prefilter_s, r.filter_s,
                    r.focal_rmse, r.neighbour_rmse);
                io::write_aovs(only(filtered, kRgb),
                               out_dir + "/" + (maaf ? "maaf_" : "aaf_") + std::to_string(spp) + ".exr");
            }
            rows.push_back({"input", spp, spp_sum / (double(width) * height), rmse(noisy, reference),
                            timings.maaf6_sampling_s, 0.0, 0.0, 0.0, 0.0});
        }
        const std::string output = out_dir + "/maaf6_study.csv";
        const std::string temporary = io::temporary_path_for(output);
        {
            std::ofstream csv(temporary);
            csv << "method,spp,mean_spp,rmse,sampling_s,prefilter_s,filter_s,focal_rmse,neighbour_rmse\n";
            for (const Row &r : rows)
                csv << r.method << ',' << r.spp << ',' << r.mean_spp << ',' << r.rmse << ',' << r.sampling_s
                    << ',' << r.prefilter_s << ',' << r.filter_s << ',' << r.focal_rmse << ','
                    << r.neighbour_rmse << '\n';
            if (!csv) throw Error(output + ": cannot write");
        }
        io::commit_temporary(temporary, output);
    } catch (const std::exception &e) {
        std::cerr << "maaf6_study: error: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
