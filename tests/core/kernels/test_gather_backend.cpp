// The gather's backend seam (gather.h GatherBackend): every sweep of the
// methods' gathers runs on the backend their settings name.
#include <catch2/catch.hpp>
#include <cstring>
#include <random>
#include <vector>

#include "aaf/core/kernels/gather.h"

using namespace aaf;

namespace {

GatherGuides flat_guides(int width, int height) {
    GatherGuides g;
    g.resize(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::size_t i = g.index(x, y);
            g.coord_u_m[i] = x * 0.01f;
            g.coord_v_m[i] = y * 0.01f;
            g.normal_z[i] = 1.0f;
            g.object_id[i] = 1.0f;
            g.inv_two_sigma_sq[i] = 1.0f / (2.0f * 0.03f * 0.03f);
            g.radius_px[i] = 4;
        }
    return g;
}

/// Records each sweep and runs it on the CPU's backend, or, with
/// `write_zeros`, writes 0 to every output instead.
class RecordingBackend final : public GatherBackend {
  public:
    explicit RecordingBackend(bool write_zeros = false) : write_zeros_(write_zeros) {}
    void sweep(const GatherSweepRequest &request) const override {
        requests.push_back(request);
        if (!write_zeros_) return cpu_gather_backend().sweep(request);
        const std::size_t pixels = std::size_t(request.guides->width) * std::size_t(request.guides->height);
        for (std::size_t k = 0; k < request.channels; ++k)
            std::fill(request.outputs[k], request.outputs[k] + pixels, 0.0f);
    }
    mutable std::vector<GatherSweepRequest> requests;

  private:
    bool write_zeros_;
};

std::vector<float> noise(std::size_t count) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<float> v(count);
    for (float &x : v) x = u(rng);
    return v;
}

}  // namespace

TEST_CASE("Gather: every sweep of gather() and gather_modulated() runs on the backend the settings name",
          "[gather]") {
    const int w = 40, h = 30;
    const GatherGuides g = flat_guides(w, h);
    // Six channels: more than one CPU sweep's four, still one request per sweep.
    std::vector<std::vector<float>> sources(6, noise(std::size_t(w) * h));
    for (std::size_t k = 0; k < sources.size(); ++k) sources[k][k] += 1.0f;
    std::vector<ConstPlaneView> in;
    for (const auto &s : sources) in.push_back(plane_view(s.data(), w, h));
    auto run = [&](const GatherSettings &settings, bool modulated) {
        std::vector<std::vector<float>> out(sources.size(), std::vector<float>(std::size_t(w) * h, -1.0f));
        std::vector<PlaneView> views;
        for (auto &o : out) views.push_back(plane_view(o.data(), w, h));
        if (modulated)
            gather_modulated(g, settings, in, views, {}, {}, GatherNormalisation::WeightSum);
        else
            gather(g, settings, in, views);
        return out;
    };
    for (const GatherMode mode : {GatherMode::Separable, GatherMode::Full2D})
        for (const bool modulated : {false, true}) {
            INFO("mode " << int(mode) << ", modulated " << modulated);
            GatherSettings cpu;
            cpu.mode = mode;
            const auto expected = run(cpu, modulated);
            RecordingBackend recording;
            GatherSettings through = cpu;
            through.backend = &recording;
            const auto got = run(through, modulated);
            for (std::size_t k = 0; k < got.size(); ++k)
                CHECK(std::memcmp(got[k].data(), expected[k].data(), got[k].size() * sizeof(float)) == 0);
            const std::size_t sweeps = !modulated && mode == GatherMode::Separable ? 2 : 1;
            REQUIRE(recording.requests.size() == sweeps);
            for (const GatherSweepRequest &r : recording.requests) {
                CHECK(r.channels == sources.size());
                CHECK(r.guides == &g);
                CHECK((r.modulation_u != nullptr) == modulated);
            }
            if (sweeps == 2) {  // a vertical sweep, then a horizontal one
                CHECK((!recording.requests[0].along_x && recording.requests[0].along_y));
                CHECK((recording.requests[1].along_x && !recording.requests[1].along_y));
            }
            // The outputs are the backend's: one that writes zeros gives zeros.
            RecordingBackend zeros(true);
            through.backend = &zeros;
            for (const auto &plane : run(through, modulated))
                for (const float v : plane) REQUIRE(v == 0.0f);
        }
}
