#include "aov_groups.h"

namespace aaf::trace {

namespace {

/// The tracer's own channels, read back only by a resumption: no aaf::Role.
constexpr const char *kWeightChannel = "progress.weight";
constexpr const char *kUnoccludedChannel = "progress.unoccluded";
constexpr const char *kRadianceChannels[3] = {"progress.radiance.R", "progress.radiance.G",
                                              "progress.radiance.B"};

/// The per-pixel sums of a progressive render, stored in float, which a
/// resumed render continues from (the samples taken and the occluder
/// distances are the shadow group's): the key light's samples' summed
/// light-function weights, the same over the unoccluded ones, and the summed
/// radiance traced apart from r(x) V(x).
class ProgressGroup final : public AovAccumulator {
  public:
    AovGroupInfo info() const override {
        return group_info("progress",
                          "progress.weight, progress.unoccluded, progress.radiance.R/G/B (for --resume)",
                          roles());
    }
    std::vector<Role> roles() const override { return {}; }

    void write(const RenderState &state, AovSet &aovs) const override {
        const PlaneView weight = add_float_channel(aovs, kWeightChannel);
        const PlaneView unoccluded = add_float_channel(aovs, kUnoccludedChannel);
        const std::vector<PlaneView> radiance = {add_float_channel(aovs, kRadianceChannels[0]),
                                                 add_float_channel(aovs, kRadianceChannels[1]),
                                                 add_float_channel(aovs, kRadianceChannels[2])};
        state.for_each_pixel([&](int x, int y, const PrimaryHit &, const ShadowStats &s) {
            weight(x, y) = float(s.weight_sum);
            unoccluded(x, y) = float(s.unoccluded_weight_sum);
            set3(radiance, x, y,
                 {float(s.radiance_sum[0]), float(s.radiance_sum[1]), float(s.radiance_sum[2])});
        });
    }

    std::vector<std::string> resume_channels() const override {
        return {kWeightChannel, kUnoccludedChannel, kRadianceChannels[0], kRadianceChannels[1],
                kRadianceChannels[2]};
    }
    void restore(const AovSet &partial, std::vector<ShadowStats> &stats) override {
        const ConstPlaneView weight = partial.channel(kWeightChannel),
                             unoccluded = partial.channel(kUnoccludedChannel);
        const ConstPlaneView radiance[3] = {partial.channel(kRadianceChannels[0]),
                                            partial.channel(kRadianceChannels[1]),
                                            partial.channel(kRadianceChannels[2])};
        for (int y = 0; y < partial.height(); ++y)
            for (int x = 0; x < partial.width(); ++x) {
                ShadowStats &s = stats[std::size_t(y) * partial.width() + x];
                s.weight_sum = weight(x, y);
                s.unoccluded_weight_sum = unoccluded(x, y);
                for (int c = 0; c < 3; ++c) s.radiance_sum[c] = radiance[c](x, y);
            }
    }

  private:
    /// Sums are kept at full float precision, like every channel a checkpoint continues from.
    static PlaneView add_float_channel(AovSet &aovs, const std::string &name) {
        const PlaneView view = aovs.add_channel(name);
        aovs.set_precision(name, Precision::Float);
        return view;
    }
};

}  // namespace

std::unique_ptr<AovAccumulator> make_progress_group() {
    return std::make_unique<ProgressGroup>();
}

}  // namespace aaf::trace
