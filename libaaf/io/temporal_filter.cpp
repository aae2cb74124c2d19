// A method's per-frame filter with a temporal window over its sequence (temporal_filter.h).
#include "aaf/io/temporal_filter.h"

#include <algorithm>
#include <array>
#include <filesystem>
#include <limits>
#include <map>
#include <utility>

#include "aaf/core/util/error.h"
#include "aaf/io/sequence.h"

namespace aaf::io {

namespace {

/// The channels the window reads of every frame: the blended ones and the guides.
struct WindowChannels {
    std::vector<std::string> blended;
    std::array<std::string, 3> position, normal;
    std::array<std::string, 2> motion;
    std::string object_id, pixel_size;  ///< empty: the frame has none
};

bool contains(const std::vector<Role> &roles, Role role) {
    return std::find(roles.begin(), roles.end(), role) != roles.end();
}

/// A guide role's channels in `output`, required: `count` of them.
template <std::size_t N>
std::array<std::string, N> required_guide(Role role, const ChannelMap &resolved, const AovSet &output) {
    const std::vector<std::string> &names = resolved.channels(role);
    bool present = names.size() == N;
    for (const std::string &name : names) present = present && output.has_channel(name);
    if (!present) {
        std::string list;
        for (const std::string &name : names) list += (list.empty() ? "" : ", ") + name;
        throw InputError(std::string("--temporal-window needs the ") + role.key + " layer (" + list +
                         "; aaf render --aovs METHOD,position,normal,motion writes it, --map " + role.key +
                         "=... names another)");
    }
    std::array<std::string, N> channels;
    std::copy(names.begin(), names.end(), channels.begin());
    return channels;
}

/// An optional one-channel guide: its name when `output` has it, else "".
std::string optional_guide(Role role, const ChannelMap &resolved, const AovSet &output) {
    const std::vector<std::string> &names = resolved.channels(role);
    return names.size() == 1 && output.has_channel(names.front()) ? names.front() : std::string();
}

/// What the window reads of the frames `plan` filters: the outputs of the
/// method that ran (its widths aside), the beauty it composed, the guides.
WindowChannels window_channels(const FilterPlan &plan, const ChannelMap &resolved, const AovSet &output) {
    WindowChannels channels;
    const MethodRoles &roles = plan.method->info().roles;
    for (Role role : roles.outputs) {
        if (contains(roles.widths, role)) continue;
        for (const std::string &name : plan.channels.channels(role))
            if (output.has_channel(name)) channels.blended.push_back(name);
    }
    channels.position = required_guide<3>(Role::Position, resolved, output);
    channels.normal = required_guide<3>(Role::Normal, resolved, output);
    channels.motion = required_guide<2>(Role::Motion, resolved, output);
    channels.object_id = optional_guide(Role::ObjectId, resolved, output);
    channels.pixel_size = optional_guide(Role::PixelSize, resolved, output);
    return channels;
}

std::vector<std::string> all_names(const WindowChannels &channels) {
    std::vector<std::string> names = channels.blended;
    names.insert(names.end(), channels.position.begin(), channels.position.end());
    names.insert(names.end(), channels.normal.begin(), channels.normal.end());
    names.insert(names.end(), channels.motion.begin(), channels.motion.end());
    for (const std::string *name : {&channels.object_id, &channels.pixel_size})
        if (!name->empty()) names.push_back(*name);
    return names;
}

/// The window's channels of a frame's output, copied: what is kept of it.
/// The motion follows the contract's convention (another renderer's pass,
/// synonym_scale()).
AovSet kept_channels(const AovSet &output, const WindowChannels &channels, const std::string &source) {
    AovSet kept(output.width(), output.height());
    const std::vector<std::string> motion(channels.motion.begin(), channels.motion.end());
    const std::vector<float> motion_scale = synonym_scale(Role::Motion, motion);
    for (const std::string &name : all_names(channels)) {
        if (!output.has_channel(name))
            throw InputError(source + ": no channel '" + name +
                             "' for the temporal window (the other frames of the window have it)");
        ConstPlaneView from = output.channel(name);
        PlaneView to = kept.add_channel(name);
        const auto m = std::find(motion.begin(), motion.end(), name);
        const float scale = m == motion.end() ? 1.0f : motion_scale[std::size_t(m - motion.begin())];
        std::transform(from.data, from.data + output.pixel_count(), to.data,
                       [scale](float value) { return scale * value; });
    }
    return kept;
}

/// A kept frame as the blend reads it; `values`, when given, holds the
/// planes to blend instead of the kept copies (the centre's own output).
TemporalFrameView frame_view(const AovSet &frame, const WindowChannels &channels, int offset,
                             const AovSet *values = nullptr) {
    TemporalFrameView view;
    view.offset = offset;
    for (const std::string &name : channels.blended)
        view.values.push_back((values ? *values : frame).channel(name));
    for (int c = 0; c < 3; ++c) {
        view.position[c] = frame.channel(channels.position[c]);
        view.normal[c] = frame.channel(channels.normal[c]);
    }
    for (int c = 0; c < 2; ++c) view.motion[c] = frame.channel(channels.motion[c]);
    if (!channels.object_id.empty()) view.object_id = frame.channel(channels.object_id);
    if (!channels.pixel_size.empty()) view.pixel_size_m = frame.channel(channels.pixel_size);
    return view;
}

/// What the wrapped filter keeps between frames.
struct WindowState {
    FrameFilter per_frame;
    std::string pattern;
    TemporalWindowSettings settings;
    FilterFileOptions options;
    std::shared_ptr<const int> frame;
    std::map<int, AovSet> kept;    ///< frame -> its per-frame output's window channels
    std::map<int, AovSet> inputs;  ///< frame -> its input's width inputs and guides
};

/// One width input channel a temporal window steadies (WindowWidthInput).
struct SteadiedChannel {
    std::string source, steady;
    WindowExtreme extreme;
};

/// The method's width input channels `input` holds, with where their extremes go.
std::vector<SteadiedChannel> steadied_channels(const FilterPlan &plan, const AovSet &input) {
    std::vector<SteadiedChannel> steadied;
    for (const WindowWidthInput &width : plan.method->info().roles.window_widths) {
        const std::vector<std::string> &sources = plan.channels.channels(width.source);
        const std::vector<std::string> &steady = plan.channels.channels(width.steady);
        const auto steadied_count = std::size_t(std::count_if(width.extremes.begin(), width.extremes.end(),
                                                              [](const auto &e) { return e.has_value(); }));
        if (sources.size() != width.extremes.size() || steady.size() != steadied_count)
            throw Error("temporal window: the width input '" + std::string(width.source.key) +
                        "' declares other channels than its roles have");
        std::size_t next = 0;  // the steady role's channel for the next steadied one
        for (std::size_t c = 0; c < sources.size(); ++c) {
            if (!width.extremes[c]) continue;
            const std::string &target = steady[next++];
            if (input.has_channel(sources[c])) steadied.push_back({sources[c], target, *width.extremes[c]});
        }
    }
    return steadied;
}

/// Writes the extremes of the method's width inputs (MethodRoles::window_widths)
/// over the window's frames into `input`, frame `*state.frame`'s: in place,
/// or into the steady role's channels, added (temporal_window_extrema());
/// each neighbour's inputs are read once while the window needs them.
void steady_widths(WindowState &state, const ChannelMap &resolved,
                   const std::vector<SteadiedChannel> &steadied, AovSet &input) {
    WindowChannels channels;
    for (const SteadiedChannel &c : steadied) channels.blended.push_back(c.source);
    channels.position = required_guide<3>(Role::Position, resolved, input);
    channels.normal = required_guide<3>(Role::Normal, resolved, input);
    channels.motion = required_guide<2>(Role::Motion, resolved, input);
    channels.object_id = optional_guide(Role::ObjectId, resolved, input);
    channels.pixel_size = optional_guide(Role::PixelSize, resolved, input);

    const int frame = *state.frame;
    const std::vector<int> frames = temporal_window_frames(state.pattern, frame, state.settings);
    state.inputs.erase(state.inputs.begin(), state.inputs.lower_bound(frames.front()));
    state.inputs.erase(state.inputs.upper_bound(frames.back()), state.inputs.end());
    FrameFilter read_only = state.per_frame;
    read_only.run = [](const FilterPlan &, AovSet read) { return read; };
    for (int other : frames) {
        if (other == frame || state.inputs.count(other)) continue;
        const std::string path = frame_path(state.pattern, other);
        FilterFileReport ignored;  // its own run reports it
        state.inputs.emplace(
            other,
            kept_channels(filter_file_in_memory(path, read_only, state.options, ignored), channels, path));
    }
    const AovSet own = kept_channels(input, channels, frame_path(state.pattern, frame));
    for (const SteadiedChannel &c : steadied)
        if (c.steady != c.source && !input.has_channel(c.steady)) input.add_channel(c.steady);
    for (const WindowExtreme extreme :
         {WindowExtreme::Min, WindowExtreme::Max, WindowExtreme::MinNonNegative}) {
        WindowChannels part = channels;
        part.blended.clear();
        std::vector<PlaneView> out;
        for (const SteadiedChannel &c : steadied)
            if (c.extreme == extreme) {
                part.blended.push_back(c.source);
                out.push_back(input.channel(c.steady));
            }
        if (part.blended.empty()) continue;
        std::vector<TemporalFrameView> neighbours;
        for (int other : frames)
            if (other != frame) neighbours.push_back(frame_view(state.inputs.at(other), part, other - frame));
        temporal_window_extrema(frame_view(own, part, 0), neighbours, state.settings, extreme, out);
    }
}

/// The output of the filter run on steadied inputs with the frame's own
/// inputs as they were read: the extremes are the filter's, not the file's.
void restore_inputs(const std::vector<SteadiedChannel> &steadied, const AovSet &alone, AovSet &output) {
    for (const SteadiedChannel &c : steadied) {
        if (c.steady != c.source) {
            if (output.has_channel(c.steady)) output.take_channel(c.steady);
            continue;
        }
        if (!output.has_channel(c.source) || !alone.has_channel(c.source)) continue;
        const ConstPlaneView from = alone.channel(c.source);
        const PlaneView to = output.channel(c.source);
        for (int y = 0; y < to.height; ++y)
            for (int x = 0; x < to.width; ++x) to(x, y) = from(x, y);
    }
}

/// Blends `output`, frame `*state.frame`'s per-frame output, with its window.
/// `per_frame`: the frame filtered alone, what its neighbours blend (the
/// same whichever frame filtered it first).
void blend_window(WindowState &state, const FilterPlan &plan, const ChannelMap &resolved, AovSet &output,
                  const AovSet &per_frame) {
    const int frame = *state.frame;
    const WindowChannels channels = window_channels(plan, resolved, output);
    const std::vector<int> frames = temporal_window_frames(state.pattern, frame, state.settings);
    // Frames before the window are not needed again by a sequence in order.
    state.kept.erase(state.kept.begin(), state.kept.lower_bound(frames.front()));
    state.kept.erase(state.kept.upper_bound(frames.back()), state.kept.end());
    state.kept.insert_or_assign(frame, kept_channels(per_frame, channels, frame_path(state.pattern, frame)));
    for (int other : frames) {
        if (state.kept.count(other)) continue;
        const std::string path = frame_path(state.pattern, other);
        FilterFileReport ignored;  // its own run reports it
        state.kept.emplace(other,
                           kept_channels(filter_file_in_memory(path, state.per_frame, state.options, ignored),
                                         channels, path));
    }
    const TemporalFrameView centre = frame_view(state.kept.at(frame), channels, 0, &output);
    std::vector<TemporalFrameView> neighbours;
    for (int other : frames)
        if (other != frame) neighbours.push_back(frame_view(state.kept.at(other), channels, other - frame));
    std::vector<PlaneView> out;
    for (const std::string &name : channels.blended) out.push_back(output.channel(name));
    blend_temporal_window(centre, neighbours, state.settings, out);
}

}  // namespace

std::vector<int> temporal_window_frames(const std::string &pattern, int frame,
                                        const TemporalWindowSettings &settings) {
    const auto on_disk = [&pattern](long long other) {
        if (other < std::numeric_limits<int>::min() || other > std::numeric_limits<int>::max()) return false;
        std::error_code error;
        return std::filesystem::exists(frame_path(pattern, int(other)), error);
    };
    // Frames on disk on each side, up to the first missing one.
    int before = 0, after = 0;
    while (before < settings.radius_frames && on_disk(frame - 1LL - before)) ++before;
    while (!settings.causal && after < settings.radius_frames && on_disk(frame + 1LL + after)) ++after;
    // Centred: as many frames after as before, so that a steady change (a
    // light or a shadow moving at constant speed) averages to the frame's own value.
    if (!settings.causal) before = after = std::min(before, after);
    std::vector<int> frames;
    for (int other = frame - before; other <= frame + after; ++other) frames.push_back(other);
    return frames;
}

FrameFilter temporal_filter(FrameFilter filter, const std::string &pattern,
                            const TemporalWindowSettings &settings, const FilterFileOptions &options,
                            std::shared_ptr<const int> frame) {
    if (filter.reads_history)
        throw Error(
            "--temporal-window: this filter already reads its previous frame's output; use one "
            "temporal filter");
    auto state = std::make_shared<WindowState>();
    state->per_frame = filter;
    state->pattern = pattern;
    state->settings = settings;
    state->options = options;
    state->options.keep_beauty = false;  // the window blends the filter's own beauty
    state->frame = std::move(frame);
    filter.run = [state, run = filter.run](const FilterPlan &plan, AovSet input) {
        const ChannelMap resolved = state->options.channels.resolved(input);
        // Steadied widths change the frame's own filtering; its neighbours
        // blend it as filtered alone, so that is filtered too (twice the
        // filter's time for AAF, whose widths come from its inputs).
        const std::vector<SteadiedChannel> steadied = steadied_channels(plan, input);
        if (steadied.empty()) {
            AovSet output = run(plan, std::move(input));
            blend_window(*state, plan, resolved, output, output);
            return output;
        }
        AovSet steady = input;
        steady_widths(*state, resolved, steadied, steady);
        AovSet alone = run(plan, std::move(input));
        AovSet output = run(plan, std::move(steady));
        restore_inputs(steadied, alone, output);
        blend_window(*state, plan, resolved, output, alone);
        return output;
    };
    return filter;
}

}  // namespace aaf::io
