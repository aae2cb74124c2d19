#include <algorithm>
#include <cstdint>
#include <vector>

#include "aaf/core/methods/maaf/maaf_accumulation.h"
#include "aaf/core/methods/maaf/maaf_roles.h"
#include "aaf/core/methods/maaf/maaf_wedge.h"
#include "aov_groups.h"

namespace aaf::trace {

const ParameterDeclarations<MaafGroupSettings> &maaf_group_parameters() {
    using P = MaafGroupSettings;
    static const auto declarations = std::move(ParameterDeclarations<P>("maaf").integer(
        "maaf_first_pass_spp", &P::first_pass_spp, "samples per pixel",
        "the samples of MAAF's first pass (Sec. 6.2), a pass of their own that sets the wedges", 1, 1 << 20));
    return declarations;
}

namespace {

/// MAAF's light-side sums (Wu et al. 2017, MAAF Eq. 20/23) in two passes as the
/// paper's Sec. 6: the pixel's first batch of samples (render.cpp traces
/// first_pass_spp() of them, the group's parameter, as their own stratified pass)
/// gives the occluder distances, hence the wedge (prefiltered over 5x5,
/// Sec. 6.2) and the light-side frequencies C_y^p; then every sample of the
/// pixel, the first batch's included, is accumulated with those. The samples
/// are kept until write(), which computes the wedges and the sums: 20 bytes
/// per sample (a 640x480 render at 16 spp keeps about 100 MB).
class MaafGroup final : public AovAccumulator {
  public:
    AovGroupInfo info() const override {
        AovGroupInfo info =
            group_info("maaf",
                       "maaf.V_<a><b> and maaf.W_<a><b> (25 each, N = 3), maaf.smin, maaf.smax, maaf.omegax, "
                       "maaf.omegay; two passes (the first, of --maaf-first-pass-spp samples or spp if "
                       "fewer, gives the wedges)",
                       roles());
        info.parameters = maaf_group_parameters().infos();
        info.not_resumable_because = "they need every sample, kept in memory";
        return info;
    }
    std::vector<Role> roles() const override {
        return {roles::MaafValueSums, roles::MaafUnoccludedSums, roles::MaafWedge};
    }
    bool wants_samples() const override { return true; }
    void set_parameters(const ParameterSet &values) override {
        settings_ = maaf_group_parameters().read(values);
    }
    int first_pass_spp() const override { return settings_.first_pass_spp; }

    void begin_render(std::size_t pixel_count) override {
        samples_.assign(pixel_count, {});
        first_batch_size_.assign(pixel_count, 0);
        batches_.assign(pixel_count, 0);
    }
    void add_sample(std::size_t pixel, const LightSample &sample) override {
        if (!sample.has_receiver) return;
        const float weight = float(sample.weight);
        samples_[pixel].push_back({sample.y_u_m, sample.y_v_m, sample.visible ? weight : 0.0f, weight,
                                   sample.visible ? 0.0f : sample.d2_m});
    }
    void end_pixel(std::size_t pixel) override {
        if (batches_[pixel]++ == 0) first_batch_size_[pixel] = std::uint32_t(samples_[pixel].size());
    }

    void write(const RenderState &state, AovSet &aovs) const override {
        const int width = state.width, height = state.height;
        const std::size_t count = std::size_t(width) * std::size_t(height);
        const LightPlane &light = state.scene.key_light();

        // The first pass's view of the shadow (MAAF Sec. 6.2 "Sampling").
        std::vector<float> d1(count, 0.0f), d2_min(count, 0.0f), d2_max(count, 0.0f), id(count, 0.0f),
            pixel_size(count, 0.0f), normal[3];
        for (std::vector<float> &n : normal) n.assign(count, 0.0f);
        state.for_each_pixel([&](int x, int y, const PrimaryHit &primary, const ShadowStats &) {
            const std::size_t i = std::size_t(y) * std::size_t(width) + std::size_t(x);
            if (!primary.found) return;
            d1[i] = light.plane_distance_m(primary.position);
            id[i] = float(primary.mesh->object_id);
            pixel_size[i] = primary.pixel_size_m;
            normal[0][i] = primary.normal.x;
            normal[1][i] = primary.normal.y;
            normal[2][i] = primary.normal.z;
            float nearest = 0, farthest = 0;
            for (std::uint32_t k = 0; k < first_batch_size_[i]; ++k) {
                const float d2 = samples_[i][k].d2_m;
                if (!(d2 > 0)) continue;
                nearest = nearest > 0 ? std::min(nearest, d2) : d2;
                farthest = std::max(farthest, d2);
            }
            d2_min[i] = nearest;
            d2_max[i] = farthest;
        });
        auto view = [&](const std::vector<float> &plane) { return plane_view(plane.data(), width, height); };
        MaafWedgeInputs inputs;
        inputs.d1 = view(d1);
        inputs.d2_min = view(d2_min);
        inputs.d2_max = view(d2_max);
        for (std::size_t c = 0; c < 3; ++c) inputs.normal[c] = view(normal[c]);
        inputs.object_id = view(id);
        inputs.pixel_size = view(pixel_size);
        MaafWedgeParams params;
        const MaafWedges wedges = maaf_pixel_wedges(inputs, light, params);

        const auto value_views = add_role_channels(aovs, roles::MaafValueSums);
        const auto unoccluded_views = add_role_channels(aovs, roles::MaafUnoccludedSums);
        const auto wedge_views = add_role_channels(aovs, roles::MaafWedge);
        const int channels = maaf_channel_count(kMaafContractPairs);
        std::vector<double> value_sums(static_cast<std::size_t>(channels), 0.0),
            unoccluded_sums(static_cast<std::size_t>(channels), 0.0);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                const std::size_t i = std::size_t(y) * std::size_t(width) + std::size_t(x);
                // MAAF Sec. 6.2 "Pre-filtering": MAAF Eq. 20/23 with the pixel's parameters, over all its
                // samples.
                const MaafLightSide light_side(kMaafContractPairs, double(wedges.omega_y[i]));
                std::fill(value_sums.begin(), value_sums.end(), 0.0);
                std::fill(unoccluded_sums.begin(), unoccluded_sums.end(), 0.0);
                for (const Stored &s : samples_[i])
                    light_side.accumulate(s.y1_m, s.y2_m, s.value, s.unoccluded, value_sums.data(),
                                          unoccluded_sums.data());
                for (int c = 0; c < channels; ++c) {
                    value_views[std::size_t(c)](x, y) = float(value_sums[std::size_t(c)]);
                    unoccluded_views[std::size_t(c)](x, y) = float(unoccluded_sums[std::size_t(c)]);
                }
                wedge_views[0](x, y) = wedges.s_min[i];
                wedge_views[1](x, y) = wedges.s_max[i];
                wedge_views[2](x, y) = wedges.omega_x_max[i];
                wedge_views[3](x, y) = wedges.omega_y[i];
            }
        aovs.attributes[attr::kMaafPairs] = kMaafContractPairs;
        aovs.attributes[attr::kMaafOmegaYMax] = float(maaf_light_omega_y_max(light, params.light_band));
    }

  private:
    /// One sample of a pixel as MAAF needs it.
    struct Stored {
        float y1_m, y2_m;  ///< point on the light along axis_u and axis_v, metres from its centre
        float value;       ///< light weight l(y) times visibility
        float unoccluded;  ///< l(y)
        float d2_m;        ///< occluder's light-plane distance; 0 when unoccluded
    };
    std::vector<std::vector<Stored>> samples_;
    std::vector<std::uint32_t> first_batch_size_;
    std::vector<std::uint32_t> batches_;
    MaafGroupSettings settings_;
};

}  // namespace

std::unique_ptr<AovAccumulator> make_maaf_group() {
    return std::make_unique<MaafGroup>();
}

}  // namespace aaf::trace
