#pragma once

#include <cmath>
#include <cstdlib>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

namespace aaf {

/// The kind of value a method parameter holds. A Text is any string, which
/// its owner parses (a list such as "defocus,shadows").
enum class ParameterType { Float, Int, Bool, Choice, Text };

/// One parameter a method declares: what the command line, `aaf info`, the
/// Python module and the property tests are generated from.
struct ParameterInfo {
    std::string name;  ///< snake_case; the command line spells it --with-dashes
    ParameterType type = ParameterType::Float;
    std::string default_value;  ///< as text: "2", "true", "separable"
    std::string unit;           ///< "metres", "pixels", "degrees", "" when dimensionless
    std::string help;           ///< one line
    /// Valid range of a Float or Int; an open end excludes its bound.
    double min = -std::numeric_limits<double>::infinity();
    double max = std::numeric_limits<double>::infinity();
    bool min_open = false, max_open = false;
    std::vector<std::string> choices;  ///< the values of a Choice

    /// The valid values in words: "(0, 1]", ">= 0", "separable|2d", "true|false".
    std::string range_text() const;
    /// The command-line spelling: "--normal-threshold" for normal_threshold.
    std::string option_name() const;

    /// A Float in [min, max] (an open end excludes its bound).
    static ParameterInfo real(std::string name, std::string default_value, std::string unit, std::string help,
                              double min, double max = std::numeric_limits<double>::infinity(),
                              bool min_open = false, bool max_open = false);
    /// An Int in [min, max].
    static ParameterInfo integer(std::string name, std::string default_value, std::string unit,
                                 std::string help, int min, int max);
    /// A Bool, off unless given.
    static ParameterInfo flag(std::string name, std::string help);
    /// One of `choices`.
    static ParameterInfo choice(std::string name, std::string default_value, std::vector<std::string> choices,
                                std::string help);
    /// A Text, checked by its owner.
    static ParameterInfo text(std::string name, std::string default_value, std::string unit,
                              std::string help);
};

/// Values of a method's parameters, every one set to its default until
/// changed. Setting checks the name and the range, so a set always holds
/// valid values.
class ParameterSet {
  public:
    ParameterSet() = default;
    /// Defaults of `infos`; `owner` names the method in error messages.
    ParameterSet(std::string owner, std::vector<ParameterInfo> infos);

    /// Parses and sets one value. Throws aaf::Error, one line naming the
    /// method and parameter: unknown name (with the known ones), a value that
    /// does not parse, or one out of range.
    void set(const std::string &name, const std::string &value);
    void set(const std::string &name, double value);
    void set(const std::string &name, bool value);

    float get_float(const std::string &name) const;
    int get_int(const std::string &name) const;
    bool get_bool(const std::string &name) const;
    const std::string &get_choice(const std::string &name) const;
    const std::string &get_text(const std::string &name) const;

    const std::vector<ParameterInfo> &infos() const { return infos_; }
    const ParameterInfo &info(const std::string &name) const;
    /// The current value as text ("2.5", "true", "separable").
    std::string text(const std::string &name) const;

  private:
    using Value = std::variant<double, bool, std::string>;
    const Value &value(const std::string &name, ParameterType type) const;
    void check_range(const ParameterInfo &info, double value) const;

    std::string owner_;
    std::vector<ParameterInfo> infos_;
    std::map<std::string, Value> values_;
};

/// A value as a parameter's text: the shortest decimal that reads back as the
/// same float ("2", "0.001", "0.2"), or double; an integer as such;
/// "true"/"false". What defaults and written values are shown as.
std::string parameter_text(float value);
std::string parameter_text(double value);
std::string parameter_text(long long value);
std::string parameter_text(bool value);

/// Throws aaf::Error: a value of choice parameter `name` that its declaration does not name.
[[noreturn]] void throw_unnamed_choice(const std::string &name);
/// Throws aaf::Error as ParameterSet::info() does for a name `infos` lacks.
[[noreturn]] void throw_unknown_parameter(const std::string &owner, const std::vector<ParameterInfo> &infos,
                                          const std::string &name);

/// Each parameter of a method declared once, bound to the member of its
/// settings struct `Params` that it sets (pbrt-v4's ParameterDictionary
/// lookups, but typed): the ParameterInfo the command line, `aaf info`, the
/// Python module and provenance are generated from, its default the text of
/// Params{}'s member (its default member initialiser), and the copies from a
/// ParameterSet to a Params and back.
///
///     static const auto declarations = ParameterDeclarations<AafParams>("aaf")
///         .real("mu", &AafParams::mu, "", "Filter scale ...", 0, kInf, /*min_open=*/true)
///         .choice("light_axes", &AafParams::light_axes,
///                 {{"per_axis", AafLightAxes::PerAxis}, {"shortest", AafLightAxes::Shortest}}, "...");
///
/// A member may belong to a base of Params (settings several methods share).
template <class Params>
class ParameterDeclarations {
  public:
    /// `owner` names the method in the sets' error messages.
    explicit ParameterDeclarations(std::string owner) : owner_(std::move(owner)) {}

    /// A Float in [min, max] (an open end excludes its bound), bound to a
    /// float or double member. Read at float precision, as
    /// ParameterSet::get_float() reads it.
    template <class T, class Base>
    ParameterDeclarations &real(std::string name, T Base::*member, std::string unit, std::string help,
                                double min, double max = std::numeric_limits<double>::infinity(),
                                bool min_open = false, bool max_open = false) {
        static_assert(std::is_floating_point_v<T> && std::is_base_of_v<Base, Params>);
        ParameterInfo info = ParameterInfo::real(name, parameter_text(Params{}.*member), std::move(unit),
                                                 std::move(help), min, max, min_open, max_open);
        return add(
            std::move(info),
            Binding{
                [member, name](const ParameterSet &set, Params &p) { p.*member = T(set.get_float(name)); },
                [member, name](const Params &p, ParameterSet &set) {
                    set.set(name, decimal_value(p.*member));
                },
                [member](const Params &a, const Params &b) { return a.*member == b.*member; },
            });
    }

    /// An Int in [min, max], bound to an integer member.
    template <class T, class Base>
    ParameterDeclarations &integer(std::string name, T Base::*member, std::string unit, std::string help,
                                   int min, int max) {
        static_assert(std::is_integral_v<T> && !std::is_same_v<T, bool> && std::is_base_of_v<Base, Params>);
        ParameterInfo info = ParameterInfo::integer(name, parameter_text((long long)(Params{}.*member)),
                                                    std::move(unit), std::move(help), min, max);
        return add(
            std::move(info),
            Binding{
                [member, name](const ParameterSet &set, Params &p) { p.*member = T(set.get_int(name)); },
                [member, name](const Params &p, ParameterSet &set) { set.set(name, double(p.*member)); },
                [member](const Params &a, const Params &b) { return a.*member == b.*member; },
            });
    }

    /// A Bool (the command line's flag turns it on), bound to a bool member.
    template <class Base>
    ParameterDeclarations &flag(std::string name, bool Base::*member, std::string help) {
        static_assert(std::is_base_of_v<Base, Params>);
        ParameterInfo info = ParameterInfo::flag(name, std::move(help));
        info.default_value = parameter_text(bool(Params{}.*member));
        return add(std::move(info),
                   Binding{
                       [member, name](const ParameterSet &set, Params &p) { p.*member = set.get_bool(name); },
                       [member, name](const Params &p, ParameterSet &set) { set.set(name, bool(p.*member)); },
                       [member](const Params &a, const Params &b) { return a.*member == b.*member; },
                   });
    }

    /// A Choice among named values of a member of any type (an enum, a bool,
    /// a sample count), in the order listed; the default is the name of
    /// Params{}'s value. Throws aaf::Error when that value has no name.
    template <class T, class Base>
    ParameterDeclarations &choice(std::string name, T Base::*member,
                                  std::vector<std::pair<std::string, T>> choices, std::string help) {
        static_assert(std::is_base_of_v<Base, Params>);
        std::vector<std::string> names;
        for (const auto &c : choices) names.push_back(c.first);
        ParameterInfo info = ParameterInfo::choice(name, choice_name(name, choices, Params{}.*member),
                                                   std::move(names), std::move(help));
        return add(std::move(info),
                   Binding{
                       [member, name, choices](const ParameterSet &set, Params &p) {
                           const std::string &text = set.get_choice(name);
                           for (const auto &c : choices)
                               if (c.first == text) p.*member = c.second;
                       },
                       [member, name, choices](const Params &p, ParameterSet &set) {
                           set.set(name, choice_name(name, choices, p.*member));
                       },
                       [member](const Params &a, const Params &b) { return a.*member == b.*member; },
                   });
    }

    /// A Choice whose member holds the chosen name itself.
    template <class Base>
    ParameterDeclarations &text_choice(std::string name, std::string Base::*member,
                                       std::vector<std::string> names, std::string help) {
        std::vector<std::pair<std::string, std::string>> choices;
        for (const std::string &n : names) choices.emplace_back(n, n);
        return choice<std::string, Base>(std::move(name), member, std::move(choices), std::move(help));
    }

    /// A Text bound to a member of any type (a bit set, a list): `parse`
    /// reads the text, throwing aaf::Error for one it cannot use, and
    /// `format` is its inverse; the default is format(Params{}'s member).
    template <class T, class Base>
    ParameterDeclarations &parsed_text(std::string name, T Base::*member, T (*parse)(const std::string &),
                                       std::string (*format)(T), std::string unit, std::string help) {
        static_assert(std::is_base_of_v<Base, Params>);
        ParameterInfo info =
            ParameterInfo::text(name, format(Params{}.*member), std::move(unit), std::move(help));
        return add(std::move(info),
                   Binding{
                       [member, name, parse](const ParameterSet &set, Params &p) {
                           p.*member = parse(set.get_text(name));
                       },
                       [member, name, format](const Params &p, ParameterSet &set) {
                           set.set(name, format(p.*member));
                       },
                       [member](const Params &a, const Params &b) { return a.*member == b.*member; },
                   });
    }

    const std::string &owner() const { return owner_; }
    /// The declarations in order: MethodInfo::parameters.
    const std::vector<ParameterInfo> &infos() const { return infos_; }
    /// The declaration of `name`; throws aaf::Error naming the known ones.
    const ParameterInfo &info(const std::string &name) const {
        for (const ParameterInfo &info : infos_)
            if (info.name == name) return info;
        throw_unknown_parameter(owner_, infos_, name);
    }
    /// Every parameter at its default, Params{}'s.
    ParameterSet defaults() const { return ParameterSet(owner_, infos_); }

    /// Params{} with every declared member set from `set` (a set of these
    /// declarations); members not declared keep their default.
    Params read(const ParameterSet &set) const {
        Params params{};
        for (const Binding &binding : bindings_) binding.read(set, params);
        return params;
    }

    /// The set holding `params`' declared members. Throws aaf::Error, as
    /// ParameterSet::set(), for a value out of its declared range.
    ParameterSet write(const Params &params) const {
        ParameterSet set = defaults();
        for (const Binding &binding : bindings_) binding.write(params, set);
        return set;
    }

    /// The parameters whose default, as declared (the text --help, `aaf
    /// info`, the docs and provenance show), does not read back as Params{}'s
    /// member: empty when each default is written once and its text is exact.
    std::vector<std::string> defaults_read_back_differently() const {
        const Params read_back = read(defaults()), initialised{};
        std::vector<std::string> names;
        for (std::size_t i = 0; i < bindings_.size(); ++i)
            if (!bindings_[i].same(read_back, initialised)) names.push_back(infos_[i].name);
        return names;
    }

  private:
    struct Binding {
        std::function<void(const ParameterSet &, Params &)> read;
        std::function<void(const Params &, ParameterSet &)> write;
        std::function<bool(const Params &, const Params &)> same;
    };

    ParameterDeclarations &add(ParameterInfo info, Binding binding) {
        infos_.push_back(std::move(info));
        bindings_.push_back(std::move(binding));
        return *this;
    }

    /// The decimal a finite value is shown as, as a double (what a user
    /// typing the text gives); a non-finite one unchanged, for the range check.
    template <class T>
    static double decimal_value(T value) {
        return std::isfinite(value) ? std::strtod(parameter_text(value).c_str(), nullptr) : double(value);
    }

    template <class T>
    static std::string choice_name(const std::string &name,
                                   const std::vector<std::pair<std::string, T>> &choices, const T &value) {
        for (const auto &c : choices)
            if (c.second == value) return c.first;
        throw_unnamed_choice(name);
    }

    std::string owner_;
    std::vector<ParameterInfo> infos_;
    std::vector<Binding> bindings_;
};

}  // namespace aaf
