#pragma once

#include <limits>
#include <map>
#include <string>
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

}  // namespace aaf
