#include "aaf/core/framework/filter_aovs.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>

#include "aaf/core/contract/ratio_layers.h"
#include "aaf/core/framework/method_registry.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/frame_allocator.h"
#include "aaf/core/util/parallel.h"
#include "aaf/core/util/quoted.h"

namespace aaf {

namespace {

bool contains(const std::vector<std::string> &names, const std::string &name) {
    return std::find(names.begin(), names.end(), name) != names.end();
}

bool has_all(const AovSet &aovs, const std::vector<std::string> &names) {
    return std::all_of(names.begin(), names.end(), [&](const std::string &n) { return aovs.has_channel(n); });
}

std::string joined(const std::vector<std::string> &names) {
    std::string text;
    for (const std::string &name : names) text += (text.empty() ? "" : ",") + escaped(name);
    return text;
}

/// Moves every channel of `input` but `skip` into a new set with its
/// attributes, in their order; `input` keeps the skipped ones.
AovSet move_except(AovSet &input, const std::vector<std::string> &skip) {
    AovSet out(input.width(), input.height());
    out.attributes = input.attributes;
    const std::vector<std::string> names = input.channel_names();
    for (const std::string &name : names)
        if (!contains(skip, name)) out.add_channel(name, input.take_channel(name));
    return out;
}

/// A channel of the input, split between the output's moved planes and the rest.
struct SplitInput {
    const AovSet &moved, &rest;
    bool has_all(const std::vector<std::string> &names) const {
        for (const std::string &name : names)
            if (!moved.has_channel(name) && !rest.has_channel(name)) return false;
        return true;
    }
    ConstPlaneView channel(const std::string &name) const {
        return moved.has_channel(name) ? moved.channel(name) : rest.channel(name);
    }
};

/// Refuses a plan that is not ready, naming the first input it lacks, and a
/// frame that is not the one it was prepared for.
void check_inputs(const FilterPlan &plan, const AovSet &input) {
    if (!plan.missing.roles.empty()) {
        const RoleInfo &info = role_info(plan.missing.roles.front());
        throw InputError("missing " + plan.method->info().title + " input '" + info.role.key +
                         "' (channels " + joined(plan.channels.channels(info.role)) + ")");
    }
    if (!plan.missing.attributes.empty())
        throw InputError("missing header attribute " + quoted(plan.missing.attributes.front()));
    for (Role role : plan.method->info().roles.required)
        for (const std::string &name : plan.channels.channels(role))
            if (!input.has_channel(name))
                throw Error("the filter plan was prepared for another frame: this one lacks channel " +
                            quoted(name));
}

/// The per-light layers of `method`'s ratio roles (ratio_layers.h) in
/// `frame`, as `found` names the summed layers.
std::vector<std::string> per_light_channels(const Method &method, const AovSet &frame,
                                            const ChannelMap &found) {
    std::vector<Role> roles = method.info().roles.required;
    roles.insert(roles.end(), method.info().roles.optional.begin(), method.info().roles.optional.end());
    const int lights = ratio_light_count(frame.attributes, frame.channel_names().size());
    std::vector<std::string> names;
    for (Role role : roles)
        if (is_per_light_role(role))
            for (int light = 0; light < lights; ++light)
                for (const std::string &name : found.channels(role))
                    names.push_back(per_light_channel(name, light));
    return names;
}

/// The read-only views of every declared input role present in `input`.
void bind_inputs(const Method &method, const SplitInput &input, const ChannelMap &found,
                 MethodImages &images) {
    std::vector<Role> roles = method.info().roles.required;
    const std::vector<Role> &optional = method.info().roles.optional;
    roles.insert(roles.end(), optional.begin(), optional.end());
    for (Role role : roles) {
        const std::vector<std::string> &names = found.channels(role);
        images.set_channel_names(role, joined(names));
        if (!input.has_all(names)) continue;
        std::vector<ConstPlaneView> views;
        for (const std::string &name : names) views.push_back(input.channel(name));
        images.set_input(role, views);
    }
    // The ratio roles' per-light layers, named after the summed layer's channels.
    const int lights = ratio_light_count(
        input.rest.attributes, input.moved.channel_names().size() + input.rest.channel_names().size());
    images.set_light_count(lights);
    for (Role role : roles) {
        if (!is_per_light_role(role)) continue;
        for (int light = 0; light < lights; ++light) {
            std::vector<std::string> names;
            for (const std::string &name : found.channels(role))
                names.push_back(per_light_channel(name, light));
            images.set_light_channel_names(role, light, joined(names));
            if (!input.has_all(names)) continue;
            std::vector<ConstPlaneView> views;
            for (const std::string &name : names) views.push_back(input.channel(name));
            images.set_light_input(role, light, views);
        }
    }
}

}  // namespace

MissingInputs missing_inputs(const Method &method, const AovSet &aovs, const ChannelMap &channels) {
    const ChannelMap found = channels.resolved(aovs);
    MissingInputs missing;
    for (Role role : method.info().roles.required)
        if (!has_all(aovs, found.channels(role))) missing.roles.push_back(role);
    for (const std::string &name : method.info().required_attributes)
        if (!aovs.attributes.count(name)) missing.attributes.push_back(name);
    return missing;
}

std::vector<std::string> method_input_channels(const Method &method, const ChannelMap &channels) {
    std::vector<Role> roles = method.info().roles.required;
    roles.push_back(Role::Beauty);
    const std::vector<Role> &optional = method.info().roles.optional;
    roles.insert(roles.end(), optional.begin(), optional.end());
    std::vector<std::string> names;
    for (Role role : roles)
        for (const std::string &name : channels.channels(role))
            if (!contains(names, name)) names.push_back(name);
    return names;
}

std::string delegate_command(const MethodDelegate &delegate) {
    const Method &method = find_method(delegate.method);
    ParameterSet parameters = method.default_parameters();
    std::string command = "aaf filter " + method.info().name;
    for (const auto &[name, value] : delegate.parameters) {
        parameters.set(name, value);  // checks the name and the value
        command += " " + parameters.info(name).option_name() + " " + value;
    }
    return command;
}

std::string delegate_parameter_refusal(const Method &method, const MethodDelegate &delegate,
                                       const std::string &parameter) {
    std::string option = parameter;
    for (const ParameterInfo &info : method.info().parameters)
        if (info.name == parameter) option = info.option_name();
    return delegate.why + " is filtered as `" + delegate_command(delegate) + "`, which does not take " +
           method.info().name + "'s " + option + ": give " + delegate.method + "'s own options (aaf filter " +
           delegate.method + " --help)";
}

MethodChoice choose_method(const Method &method, const ParameterSet &parameters, const AovSet &aovs,
                           const ChannelMap &channels) {
    MethodChoice choice{&method, parameters, {}};
    if (missing_inputs(method, aovs, channels).empty()) return choice;
    for (const MethodDelegate &delegate : method.info().delegates) {
        const Method &other = find_method(delegate.method);
        if (!missing_inputs(other, aovs, channels).empty()) continue;
        choice.method = &other;
        choice.parameters = other.default_parameters();
        for (const auto &[name, value] : delegate.parameters) choice.parameters.set(name, value);
        const std::string command = delegate_command(delegate);
        choice.note = delegate.why + " (" + other.info().name + "'s inputs): filtered as `" + command + "`";
        // The delegate's options are its own: a setting made for `method` would be silently lost.
        const ParameterSet defaults = method.default_parameters();
        for (const ParameterInfo &info : method.info().parameters)
            if (parameters.text(info.name) != defaults.text(info.name))
                throw ParameterError(delegate_parameter_refusal(method, delegate, info.name));
        return choice;
    }
    return choice;  // the plan lists what `method` lacks
}

FilterPlan prepare_filter(const Method &method, const ParameterSet &parameters, const AovSet &frame,
                          const ChannelMap &channels, Composition composition) {
    FilterPlan plan;
    plan.asked = &method;
    // Other renderers' names are found through the synonym table.
    plan.channels = channels.resolved(frame);
    MethodChoice choice = choose_method(method, parameters, frame, plan.channels);
    plan.method = choice.method;
    plan.parameters = std::move(choice.parameters);
    plan.note = std::move(choice.note);
    plan.missing = missing_inputs(*plan.method, frame, plan.channels);
    plan.input_channels = method_input_channels(*plan.method, plan.channels);
    for (const std::string &name : per_light_channels(*plan.method, frame, plan.channels))
        plan.input_channels.push_back(name);
    plan.reads_history = plan.method->reads_history(plan.parameters);
    plan.composition = composition;
    const auto has = [&](Role role) {
        const std::vector<std::string> &names = plan.channels.channels(role);
        return !names.empty() && has_all(frame, names);
    };
    // Only a plan that can run says what it will do with the beauty.
    const std::string kept =
        plan.missing.empty() ? plan.method->composition_note(frame.attributes, has, composition) : "";
    if (!kept.empty()) plan.note += (plan.note.empty() ? "" : "; ") + kept;
    return plan;
}

std::vector<std::string> filter_input_candidates(const Method &method, const AovSet &frame,
                                                 const ChannelMap &channels) {
    const ChannelMap found = channels.resolved(frame);
    std::vector<const Method *> candidates{&method};
    for (const MethodDelegate &delegate : method.info().delegates)
        candidates.push_back(&find_method(delegate.method));
    std::vector<std::string> names;
    for (const Method *candidate : candidates) {
        std::vector<std::string> more = method_input_channels(*candidate, found);
        for (const std::string &name : per_light_channels(*candidate, frame, found)) more.push_back(name);
        for (const std::string &name : more)
            if (!contains(names, name)) names.push_back(name);
    }
    return names;
}

AovSet filter_aovs(const Method &method, const AovSet &input, const ChannelMap &channels,
                   const ParameterSet &parameters, const ProgressMonitor &monitor, const AovSet *history) {
    return run_filter(prepare_filter(method, parameters, input, channels), input, monitor, history);
}

AovSet filter_aovs(const Method &method, AovSet &&input, const ChannelMap &channels,
                   const ParameterSet &parameters, const ProgressMonitor &monitor, const AovSet *history) {
    const FilterPlan plan = prepare_filter(method, parameters, input, channels);
    return run_filter(plan, std::move(input), monitor, history);
}

AovSet run_filter(const FilterPlan &plan, const AovSet &input, const ProgressMonitor &monitor,
                  const AovSet *history) {
    check_inputs(plan, input);  // before the copy
    return run_filter(plan, AovSet(input), monitor, history);
}

namespace {

/// The largest |value| of a plane, or NaN when it holds a non-finite value.
float largest_magnitude(ConstPlaneView plane) {
    float largest = 0;
    for (int y = 0; y < plane.height; ++y)
        for (int x = 0; x < plane.width; ++x) {
            const float v = plane(x, y);
            if (!std::isfinite(v)) return std::nanf("");
            largest = std::max(largest, std::fabs(v));
        }
    return largest;
}

/// Whether every value of a plane is finite: rows in parallel, and a test of
/// the exponent bits that vectorises (largest_magnitude's early exit does not).
bool all_finite(ConstPlaneView plane) {
    std::atomic<bool> finite{true};
    parallel_for_rows(plane.height, [&](int y) {
        std::uint32_t non_finite = 0;
        if (plane.pixel_stride == 1) {
            const float *const row = &plane(0, y);
            for (int x = 0; x < plane.width; ++x) {
                std::uint32_t bits;
                std::memcpy(&bits, row + x, sizeof bits);
                non_finite |= std::uint32_t((bits & 0x7f800000u) == 0x7f800000u);  // Inf or NaN
            }
        } else {
            for (int x = 0; x < plane.width; ++x) non_finite |= std::uint32_t(!std::isfinite(plane(x, y)));
        }
        if (non_finite) finite.store(false, std::memory_order_relaxed);
    });
    return finite.load();
}

/// A finite input gives a finite output: where a method's single-precision
/// sums of inputs near float's limit (3.4e38) overflowed, this throws
/// aaf::InputError naming the output and the input channel with the largest
/// values, rather than returning Inf. Inputs that were not finite to begin
/// with (a caller that did not scrub them) pass as they are.
void check_finite_outputs(const Method &method, const MethodImages &images, const ChannelMap &found,
                          const AovSet &out) {
    std::string overflowed;
    for (Role role : method.info().roles.outputs)
        for (const std::string &name : found.channels(role))
            if (overflowed.empty() && out.has_channel(name) && !all_finite(out.channel(name)))
                overflowed = name;
    if (overflowed.empty()) return;
    std::vector<Role> roles = method.info().roles.required;
    roles.insert(roles.end(), method.info().roles.optional.begin(), method.info().roles.optional.end());
    std::string largest_name;
    float largest = -1;
    for (Role role : roles) {
        if (!images.has(role)) continue;
        const std::vector<std::string> &names = found.channels(role);
        for (std::size_t c = 0; c < names.size(); ++c) {
            const float magnitude = largest_magnitude(images.input(role, c));
            if (std::isnan(magnitude)) return;
            if (magnitude > largest) {
                largest = magnitude;
                largest_name = names[c];
            }
        }
    }
    std::ostringstream value;
    value << largest;
    throw InputError("output " + quoted(overflowed) + " overflowed to a non-finite value: input channel " +
                     quoted(largest_name) + " holds values up to " + value.str() +
                     ", too large to filter in single precision (scale the image down)");
}

/// Returns the frame's freed scratch planes to the system where they fill
/// huge pages: those fault in again cheaply (2 MiB at a time, frame_allocator.cpp),
/// and kept they would add most to the caller's peak memory. Smaller planes
/// stay with the allocator for the next frame: each would fault in again
/// 4 KiB at a time, which at 640x480 cost several times AAF's whole filter
/// (bench_methods_bandwidth), while all of them together hold a few tens of MB.
void release_frame_memory_of(const AovSet &frame) {
    constexpr std::size_t kHugePageBytes = std::size_t(2) << 20;
    if (frame.pixel_count() * sizeof(float) >= kHugePageBytes) release_frame_memory();
}

AovSet run_method(const Method &method, AovSet &&input, const ChannelMap &found,
                  const ParameterSet &parameters, Composition composition, const ProgressMonitor &monitor,
                  const AovSet *history) {
    const std::vector<Role> &outputs = method.info().roles.outputs;
    const bool composes_beauty = std::find(outputs.begin(), outputs.end(), Role::Beauty) != outputs.end();

    // Outputs replace earlier filter outputs rather than piling up beside them.
    std::vector<std::string> replaced;
    for (Role role : outputs)
        for (const std::string &name : found.channels(role)) replaced.push_back(name);
    if (composes_beauty)
        for (const std::string &name : found.channels(Role::NoisyBeauty)) replaced.push_back(name);
    // The kept channels move to the output, the method reads them there: no copy of the frame.
    AovSet out = move_except(input, replaced);

    MethodImages images(input.width(), input.height(), input.attributes);
    images.set_composition(composition);
    bind_inputs(method, SplitInput{out, input}, found, images);
    if (history && (history->width() != input.width() || history->height() != input.height()))
        throw InputError("the previous frame is " + std::to_string(history->width()) + "x" +
                         std::to_string(history->height()) + ", this one " + std::to_string(input.width()) +
                         "x" + std::to_string(input.height()));
    if (history) {
        // The previous frame's channels of every role the method reads or writes.
        std::vector<Role> roles = method.info().roles.required;
        for (const std::vector<Role> *more : {&method.info().roles.optional, &outputs})
            roles.insert(roles.end(), more->begin(), more->end());
        for (Role role : roles) {
            const std::vector<std::string> &names = found.channels(role);
            if (!has_all(*history, names)) continue;
            std::vector<ConstPlaneView> views;
            for (const std::string &name : names) views.push_back(history->channel(name));
            images.set_history(role, views);
        }
    }
    for (Role role : outputs) {
        if (role == Role::Beauty) continue;
        std::vector<PlaneView> views;
        for (const std::string &name : found.channels(role)) views.push_back(out.add_channel(name));
        images.set_output(role, views);
    }
    if (composes_beauty) {
        // Made when the method asks for the beauty (compose_shadowed_beauty, at
        // its end), not before: the planes are not held beside the method's own
        // buffers. Each new beauty channel is followed by the input's, kept as
        // the noisy beauty. Nothing else adds channels meanwhile, so the order
        // is the same as if they were made here.
        images.set_deferred_output(Role::Beauty, [&out, &input, &found] {
            // The method's freed scratch planes (frame_allocator.h) go back
            // to the system before the beauty's are made, not beside them.
            release_frame_memory_of(out);
            const std::vector<std::string> &beauty = found.channels(Role::Beauty);
            const std::vector<std::string> &noisy = found.channels(Role::NoisyBeauty);
            std::vector<PlaneView> views;
            for (std::size_t c = 0; c < beauty.size(); ++c) {
                views.push_back(out.add_channel(beauty[c]));
                if (!input.has_channel(beauty[c])) continue;
                // Moved, not copied: the plane keeps its storage, so views the method
                // was given of the input's beauty stay valid.
                out.add_channel(noisy[c], input.take_channel(beauty[c]));
            }
            return views;
        });
    }
    // A filtered beauty is no longer the tracer's sum: filtering it again keeps it (with a note).
    if (composes_beauty) out.attributes.erase(attr::kBeauty);
    Progress progress(monitor);
    progress.report(0.0);
    method.run(images, parameters, progress);
    images.make_deferred_outputs();  // a method that never asked still gets its channels
    check_finite_outputs(method, images, found, out);
    // Kept for reuse, the freed scratch would add to the caller's next
    // allocations (the output file's buffers): a large frame's filter returns it.
    release_frame_memory_of(out);
    progress.report(1.0);
    return out;
}

}  // namespace

AovSet run_filter(const FilterPlan &plan, AovSet &&input, const ProgressMonitor &monitor,
                  const AovSet *history) {
    check_inputs(plan, input);
    return run_method(*plan.method, std::move(input), plan.channels, plan.parameters, plan.composition,
                      monitor, history);
}

}  // namespace aaf
