#pragma once

#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "aaf/core/aov_contract.h"
#include "aaf/core/parameters.h"
#include "aaf/core/progress.h"

namespace aaf {

/// The AOV roles a method reads and writes: its contract (libaaf/AOV_CONTRACT.md
/// lists them per method, generated from these declarations).
struct MethodRoles {
    std::vector<Role> required;  ///< cannot run without these
    std::vector<Role> optional;  ///< used when present (a parameter may make one necessary)
    /// Written, in this order. Role::Beauty here means the method composes a
    /// new beauty; the input beauty is then kept as Role::NoisyBeauty.
    std::vector<Role> outputs;
    /// (input, output) pairs where the output is a normalised filtering of
    /// the input: a constant input gives that constant (a property every
    /// method's test checks).
    std::vector<std::pair<Role, Role>> filtered;
};

/// What a method is: the declaration everything else is generated from.
struct MethodInfo {
    std::string name;       ///< `aaf filter NAME`; lower case
    std::string title;      ///< short name in messages, e.g. "AAF"
    std::string summary;    ///< one line for `aaf filter --help`
    std::string reference;  ///< the paper, e.g. "Mehta, Wang, Ramamoorthi 2012"
    MethodRoles roles;
    std::vector<ParameterInfo> parameters;
    /// Per-image header attributes the method cannot run without (attr::).
    std::vector<std::string> required_attributes;
};

/// The images a method runs on: read-only views of its input roles (those
/// present), writable views of its output roles, and the per-image
/// attributes. Built by filter_aovs(); a method sees nothing else, so it
/// cannot write outside its outputs.
class MethodImages {
  public:
    MethodImages(int width, int height, const std::map<std::string, AttributeValue> &attributes)
        : width_(width), height_(height), attributes_(&attributes) {}

    int width() const { return width_; }
    int height() const { return height_; }
    const std::map<std::string, AttributeValue> &attributes() const { return *attributes_; }

    /// True when input `role` is present (always, for a required role).
    bool has(Role role) const { return inputs_.count(role) != 0; }
    /// Channel `channel` of input `role`; throws aaf::Error when absent.
    ConstPlaneView input(Role role, std::size_t channel = 0) const;
    /// Channel `channel` of output `role`; throws aaf::Error for a role the method does not write.
    PlaneView output(Role role, std::size_t channel = 0) const;

    /// The channel names `role` was looked for under, comma-separated, for messages.
    const std::string &channel_names(Role role) const;

    void set_input(Role role, std::vector<ConstPlaneView> views) { inputs_[role] = std::move(views); }
    void set_channel_names(Role role, std::string names) { names_[role] = std::move(names); }
    void set_output(Role role, std::vector<PlaneView> views) { outputs_[role] = std::move(views); }

  private:
    int width_, height_;
    const std::map<std::string, AttributeValue> *attributes_;
    std::map<Role, std::vector<ConstPlaneView>> inputs_;
    std::map<Role, std::vector<PlaneView>> outputs_;
    std::map<Role, std::string> names_;
};

/// A filtering method. Implementations are stateless and thread-safe; each
/// lives in its own folder under libaaf/core/methods/ and is registered in
/// methods/registry.cpp (or, outside the library, with MethodRegistration).
class Method {
  public:
    virtual ~Method() = default;
    virtual const MethodInfo &info() const = 0;
    /// Writes every output role of `images` from its inputs. `parameters`
    /// holds valid values of info().parameters. Reports progress; results do
    /// not depend on the thread count (the current oneTBB arena). Throws
    /// aaf::InputError for inputs it cannot use, aaf::Cancelled when asked to stop.
    virtual void run(const MethodImages &images, const ParameterSet &parameters,
                     Progress &progress) const = 0;

    /// The parameters at their defaults.
    ParameterSet default_parameters() const { return ParameterSet(info().name, info().parameters); }
};

}  // namespace aaf
