#include "aaf/core/framework/method.h"

#include "aaf/core/util/error.h"

namespace aaf {

ConstPlaneView MethodImages::input(Role role, std::size_t channel) const {
    auto it = inputs_.find(role);
    if (it == inputs_.end() || channel >= it->second.size())
        throw Error(std::string("input '") + role.key + "' is not available to this method");
    return it->second[channel];
}

PlaneView MethodImages::output(Role role, std::size_t channel) const {
    const std::vector<PlaneView> *views = nullptr;
    if (auto it = outputs_.find(role); it != outputs_.end()) views = &it->second;
    if (auto it = deferred_outputs_.find(role); it != deferred_outputs_.end())
        views = &deferred_views(it->second);
    if (!views || channel >= views->size())
        throw Error(std::string("internal: '") + role.key + "' is not an output of this method");
    return (*views)[channel];
}

void MethodImages::set_deferred_output(Role role, std::function<std::vector<PlaneView>()> make) {
    DeferredOutput &deferred = deferred_outputs_[role];
    deferred.make = std::move(make);
    deferred_order_.push_back(role);
}

void MethodImages::make_deferred_outputs() const {
    for (Role role : deferred_order_) deferred_views(deferred_outputs_.at(role));
}

const std::vector<PlaneView> &MethodImages::deferred_views(const DeferredOutput &deferred) const {
    // The views are written once, under the flag; the map itself is never
    // changed after the method starts, so concurrent calls are safe.
    std::call_once(*deferred.made, [&] { deferred.views = deferred.make(); });
    return deferred.views;
}

const std::string &MethodImages::channel_names(Role role) const {
    static const std::string unknown = "?";
    auto it = names_.find(role);
    return it == names_.end() ? unknown : it->second;
}

ConstPlaneView MethodImages::light_input(Role role, int light, std::size_t channel) const {
    auto it = light_inputs_.find({role, light});
    if (it == light_inputs_.end() || channel >= it->second.size())
        throw Error(std::string("input '") + role.key + "' of light " + std::to_string(light) +
                    " is not available to this method");
    return it->second[channel];
}

ConstPlaneView MethodImages::history(Role role, std::size_t channel) const {
    auto it = history_.find(role);
    if (it == history_.end() || channel >= it->second.size())
        throw Error(std::string("the previous frame's '") + role.key + "' is not available");
    return it->second[channel];
}

const std::string &MethodImages::light_channel_names(Role role, int light) const {
    static const std::string unknown = "?";
    auto it = light_names_.find({role, light});
    return it == light_names_.end() ? unknown : it->second;
}

}  // namespace aaf
