#pragma once

#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/framework/parameters.h"
#include "aaf/core/framework/progress.h"
#include "aaf/core/framework/temporal_window.h"

namespace aaf {

/// A width input a temporal window steadies: each channel of `source` with
/// an extreme becomes that extreme over the window's frames at the pixel's
/// surface point (temporal_window_extrema()), in `steady`'s channels, in
/// order. `steady` equal to `source` replaces it (AAF's occluder distances);
/// another role, an optional input of the method, holds the extremes beside
/// the frame's own values (MAAF 6D's wedges, whose own values set the phases
/// its sums carry).
struct WindowWidthInput {
    Role source, steady;
    /// One per channel of `source`; std::nullopt: not steadied (no channel in `steady`).
    std::vector<std::optional<WindowExtreme>> extremes;
};

/// The AOV roles a method reads and writes: its contract (libaaf/AOV_CONTRACT.md
/// lists them per method, generated from these declarations).
struct MethodRoles {
    std::vector<Role> required;  ///< cannot run without these
    std::vector<Role> optional;  ///< used when present (a parameter may make one necessary)
    /// Optional roles a render made for this method writes too (`aaf render
    /// --aovs METHOD`): those it needs to correct the beauty rather than keep it.
    std::vector<Role> rendered;
    /// Written, in this order. Role::Beauty here means the method composes a
    /// new beauty; the input beauty is then kept as Role::NoisyBeauty.
    std::vector<Role> outputs;
    /// Outputs that describe the filter itself (AAF's per-pixel widths)
    /// rather than estimate the image: a temporal window does not blend them.
    std::vector<Role> widths;
    /// Inputs the filter's widths come from that a temporal window steadies
    /// (WindowWidthInput), so that the widths hold still from frame to frame.
    std::vector<WindowWidthInput> window_widths;
    /// (input, output) pairs where the output is a normalised filtering of
    /// the input: a constant input gives that constant (a property every
    /// method's test checks).
    std::vector<std::pair<Role, Role>> filtered;
    /// The roles this method introduces (its own inputs and outputs, e.g.
    /// MAAF's sums): their channels, units and meaning join the contract's
    /// role_table() when the method is registered. A role is declared once,
    /// here or among the shared roles (aov_contract.h).
    std::vector<RoleInfo> declared;
    /// Other renderers' (or older versions') names for declared roles.
    std::vector<RoleSynonym> synonyms;
};

/// Another method a method hands a render to when the render lacks the
/// method's own inputs but has all of the other's: `aaf filter maaf` on a
/// combined-effects render runs maaf6, `aaf filter aaf` maaf6 with one
/// filter pair (the axis-aligned filter of the same effects). The delegate
/// runs at its defaults with `parameters` set on top (choose_method(),
/// filter_aovs.h).
struct MethodDelegate {
    std::string method;                                           ///< a registered method's name
    std::vector<std::pair<std::string, std::string>> parameters;  ///< (name, value as text)
    std::string why;  ///< what such a render is, for the user's note: "a combined-effects render"
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
    /// True when the method reads the previous frame's output (MethodImages::history)
    /// on a sequence: the pipeline then keeps each frame's output for the next.
    bool uses_history = false;
    /// What `aaf compare OUT REF` measures by default: this method's output
    /// role and the role holding the same quantity in a reference render.
    /// The beauty for both, unless the estimate is not part of the beauty.
    std::pair<Role, Role> compared{Role::Beauty, Role::Beauty};
    /// Methods that filter renders made for them instead, tried in order
    /// when this method's own inputs are missing (MethodDelegate).
    std::vector<MethodDelegate> delegates;
};

/// How a method that writes Role::Beauty makes it (`aaf filter --compose`).
enum class Composition {
    /// The input beauty with only the component the method models replaced
    /// by its estimate: everything else the renderer wrote passes through.
    Correct,
    /// The paper's recomposition from the method's inputs alone (AAF Eq. 1:
    /// r(x) V(x) plus the other lights).
    Paper,
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
    /// An output whose planes `make` creates when output() first asks for
    /// them (once, thread-safe), so that they take no memory while the method
    /// works on other things first (a composed beauty, made at the end).
    void set_deferred_output(Role role, std::function<std::vector<PlaneView>()> make);
    /// Creates every deferred output not asked for yet, in the order they
    /// were declared (filter_aovs, after the method ran).
    void make_deferred_outputs() const;

    /// How the method makes Role::Beauty (Composition::Correct unless the caller chose otherwise).
    Composition composition() const { return composition_; }
    void set_composition(Composition composition) { composition_ = composition; }

    /// Per-light layers of the ratio roles (ratio_layers.h): how many lights
    /// the input declares (attr::kRatioLights, 0 = only the summed layers),
    /// whether light `light`'s channels of input `role` are all present, and
    /// those channels; light_input throws aaf::Error when absent.
    int light_count() const { return light_count_; }
    bool has_light(Role role, int light) const { return light_inputs_.count({role, light}) != 0; }
    ConstPlaneView light_input(Role role, int light, std::size_t channel = 0) const;
    /// The per-light channel names looked for, comma-separated, for messages.
    const std::string &light_channel_names(Role role, int light) const;

    void set_light_count(int count) { light_count_ = count; }
    void set_light_input(Role role, int light, std::vector<ConstPlaneView> views) {
        light_inputs_[{role, light}] = std::move(views);
    }
    void set_light_channel_names(Role role, int light, std::string names) {
        light_names_[{role, light}] = std::move(names);
    }

    /// The previous frame's output of this method, when it runs over a
    /// sequence and asked for it (MethodInfo::uses_history): whether role
    /// `role` (an input or an output role) is present in it, and its channels.
    bool has_history(Role role) const { return history_.count(role) != 0; }
    ConstPlaneView history(Role role, std::size_t channel = 0) const;
    void set_history(Role role, std::vector<ConstPlaneView> views) { history_[role] = std::move(views); }

  private:
    int width_, height_;
    const std::map<std::string, AttributeValue> *attributes_;
    std::map<Role, std::vector<ConstPlaneView>> inputs_;
    std::map<Role, std::vector<PlaneView>> outputs_;
    /// A deferred output: its maker, and the views it made (set once under `made`).
    struct DeferredOutput {
        std::function<std::vector<PlaneView>()> make;
        std::unique_ptr<std::once_flag> made = std::make_unique<std::once_flag>();
        mutable std::vector<PlaneView> views;
    };
    const std::vector<PlaneView> &deferred_views(const DeferredOutput &deferred) const;
    std::map<Role, DeferredOutput> deferred_outputs_;
    std::vector<Role> deferred_order_;
    std::map<Role, std::string> names_;
    Composition composition_ = Composition::Correct;
    int light_count_ = 0;
    std::map<std::pair<Role, int>, std::vector<ConstPlaneView>> light_inputs_;
    std::map<std::pair<Role, int>, std::string> light_names_;
    std::map<Role, std::vector<ConstPlaneView>> history_;
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

    /// Throws aaf::Error when valid values of info().parameters do not go
    /// together (a combination run() would refuse), so that a caller can say
    /// so before it reads or renders anything.
    virtual void check_parameters(const ParameterSet &parameters) const { (void)parameters; }
    /// The roles run() cannot do without under `parameters`: the required
    /// ones and the optional ones a parameter makes necessary.
    virtual std::vector<Role> roles_needed(const ParameterSet &parameters) const {
        (void)parameters;
        return info().roles.required;
    }
    /// What run() will leave as it was in the beauty of a frame with these
    /// attributes and found channels (`has(role)`), for the user's note: empty
    /// when it replaces what it models; else one sentence saying why and how
    /// to give it what it needs (e.g. another renderer's pass of the key light).
    virtual std::string composition_note(const std::map<std::string, AttributeValue> &attributes,
                                         const std::function<bool(Role)> &has,
                                         Composition composition) const {
        (void)attributes, (void)has, (void)composition;
        return {};
    }
    /// Whether run() reads the previous frame's output under `parameters`
    /// (a method with MethodInfo::uses_history may read it only when asked).
    virtual bool reads_history(const ParameterSet &parameters) const {
        (void)parameters;
        return info().uses_history;
    }
};

}  // namespace aaf
