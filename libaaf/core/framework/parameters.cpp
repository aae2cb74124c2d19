#include "aaf/core/framework/parameters.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "aaf/core/util/error.h"

namespace aaf {

namespace {

std::string number_text(double value) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.9g", value);
    return buffer;
}

/// The whole of `text` as a finite number, or false.
bool parse_number(const std::string &text, double &value) {
    if (text.empty()) return false;
    errno = 0;
    char *end = nullptr;
    value = std::strtod(text.c_str(), &end);
    return errno == 0 && end == text.c_str() + text.size() && std::isfinite(value);
}

}  // namespace

std::string ParameterInfo::range_text() const {
    switch (type) {
        case ParameterType::Bool:
            return "true|false";
        case ParameterType::Text:
            return "text";
        case ParameterType::Choice: {
            std::string text;
            for (const std::string &choice : choices) text += (text.empty() ? "" : "|") + choice;
            return text;
        }
        default:
            break;
    }
    const bool has_min = std::isfinite(min), has_max = std::isfinite(max);
    if (has_min && has_max)
        return std::string(min_open ? "(" : "[") + number_text(min) + ", " + number_text(max) +
               (max_open ? ")" : "]");
    if (has_min) return std::string(min_open ? "> " : ">= ") + number_text(min);
    if (has_max) return std::string(max_open ? "< " : "<= ") + number_text(max);
    return "any";
}

std::string ParameterInfo::option_name() const {
    std::string option = "--" + name;
    std::replace(option.begin(), option.end(), '_', '-');
    return option;
}

namespace {

ParameterInfo declared(std::string name, ParameterType type, std::string default_value, std::string help) {
    ParameterInfo p;
    p.name = std::move(name);
    p.type = type;
    p.default_value = std::move(default_value);
    p.help = std::move(help);
    return p;
}

}  // namespace

ParameterInfo ParameterInfo::real(std::string name, std::string default_value, std::string unit,
                                  std::string help, double min, double max, bool min_open, bool max_open) {
    ParameterInfo p =
        declared(std::move(name), ParameterType::Float, std::move(default_value), std::move(help));
    p.unit = std::move(unit);
    p.min = min;
    p.max = max;
    p.min_open = min_open;
    p.max_open = max_open;
    return p;
}

ParameterInfo ParameterInfo::integer(std::string name, std::string default_value, std::string unit,
                                     std::string help, int min, int max) {
    ParameterInfo p =
        real(std::move(name), std::move(default_value), std::move(unit), std::move(help), min, max);
    p.type = ParameterType::Int;
    return p;
}

ParameterInfo ParameterInfo::flag(std::string name, std::string help) {
    return declared(std::move(name), ParameterType::Bool, "false", std::move(help));
}

ParameterInfo ParameterInfo::choice(std::string name, std::string default_value,
                                    std::vector<std::string> choices, std::string help) {
    ParameterInfo p =
        declared(std::move(name), ParameterType::Choice, std::move(default_value), std::move(help));
    p.choices = std::move(choices);
    return p;
}

ParameterInfo ParameterInfo::text(std::string name, std::string default_value, std::string unit,
                                  std::string help) {
    ParameterInfo p =
        declared(std::move(name), ParameterType::Text, std::move(default_value), std::move(help));
    p.unit = std::move(unit);
    return p;
}

ParameterSet::ParameterSet(std::string owner, std::vector<ParameterInfo> infos)
    : owner_(std::move(owner)), infos_(std::move(infos)) {
    for (const ParameterInfo &info : infos_) set(info.name, info.default_value);
}

const ParameterInfo &ParameterSet::info(const std::string &name) const {
    for (const ParameterInfo &info : infos_)
        if (info.name == name) return info;
    std::string known;
    for (const ParameterInfo &info : infos_) known += (known.empty() ? "" : ", ") + info.name;
    throw Error("method '" + owner_ + "' has no parameter '" + name +
                "' (parameters: " + (known.empty() ? "none" : known) + ")");
}

void ParameterSet::check_range(const ParameterInfo &info, double value) const {
    const bool below = info.min_open ? !(value > info.min) : !(value >= info.min);
    const bool above = info.max_open ? !(value < info.max) : !(value <= info.max);
    const bool fractional = info.type == ParameterType::Int && value != std::floor(value);
    if (below || above || fractional)
        throw Error("method '" + owner_ + "': parameter '" + info.name + "' must be " +
                    (info.type == ParameterType::Int ? "an integer " : "") + "in " + info.range_text() +
                    ", got " + number_text(value));
}

void ParameterSet::set(const std::string &name, const std::string &text) {
    const ParameterInfo &p = info(name);
    auto bad = [&](const std::string &expected) {
        return Error("method '" + owner_ + "': parameter '" + name + "' expects " + expected + ", got '" +
                     text + "'");
    };
    switch (p.type) {
        case ParameterType::Bool:
            if (text != "true" && text != "false" && text != "1" && text != "0") throw bad("true or false");
            values_[name] = text == "true" || text == "1";
            return;
        case ParameterType::Choice:
            for (const std::string &choice : p.choices)
                if (choice == text) {
                    values_[name] = text;
                    return;
                }
            throw bad("one of " + p.range_text());
        case ParameterType::Text:
            values_[name] = text;
            return;
        default: {
            double value = 0;
            if (!parse_number(text, value))
                throw bad(p.type == ParameterType::Int ? "an integer" : "a number");
            set(name, value);
        }
    }
}

void ParameterSet::set(const std::string &name, double value) {
    const ParameterInfo &p = info(name);
    if (p.type != ParameterType::Float && p.type != ParameterType::Int)
        throw Error("method '" + owner_ + "': parameter '" + name + "' is not a number");
    check_range(p, value);
    values_[name] = value;
}

void ParameterSet::set(const std::string &name, bool value) {
    if (info(name).type != ParameterType::Bool)
        throw Error("method '" + owner_ + "': parameter '" + name + "' is not true/false");
    values_[name] = value;
}

const ParameterSet::Value &ParameterSet::value(const std::string &name, ParameterType type) const {
    const ParameterInfo &p = info(name);
    // An Int may be read as a float, not the other way round.
    if (p.type != type && !(type == ParameterType::Float && p.type == ParameterType::Int))
        throw Error("internal: parameter '" + name + "' of method '" + owner_ + "' read as another type");
    return values_.at(name);
}

float ParameterSet::get_float(const std::string &name) const {
    return float(std::get<double>(value(name, ParameterType::Float)));
}

int ParameterSet::get_int(const std::string &name) const {
    return int(std::get<double>(value(name, ParameterType::Int)));
}

bool ParameterSet::get_bool(const std::string &name) const {
    return std::get<bool>(value(name, ParameterType::Bool));
}

const std::string &ParameterSet::get_choice(const std::string &name) const {
    return std::get<std::string>(value(name, ParameterType::Choice));
}

const std::string &ParameterSet::get_text(const std::string &name) const {
    return std::get<std::string>(value(name, ParameterType::Text));
}

std::string ParameterSet::text(const std::string &name) const {
    const ParameterInfo &p = info(name);
    const Value &v = values_.at(name);
    if (p.type == ParameterType::Bool) return std::get<bool>(v) ? "true" : "false";
    if (p.type == ParameterType::Choice || p.type == ParameterType::Text) return std::get<std::string>(v);
    return number_text(std::get<double>(v));
}

}  // namespace aaf

namespace aaf {

namespace {

/// The shortest "%.Ng" text of `value` that `parse` reads back exactly; an
/// integral value in full ("100", not "1e+02").
template <class T, class Parse>
std::string shortest_text(T value, int max_digits, Parse parse) {
    char buffer[64];
    if (std::isfinite(value) && value == std::floor(value) && std::fabs(value) < 1e15) {
        std::snprintf(buffer, sizeof buffer, "%.0f", double(value));
        return buffer;
    }
    for (int digits = 1; digits < max_digits; ++digits) {
        std::snprintf(buffer, sizeof buffer, "%.*g", digits, double(value));
        if (parse(buffer) == value) return buffer;
    }
    std::snprintf(buffer, sizeof buffer, "%.*g", max_digits, double(value));
    return buffer;
}

}  // namespace

std::string parameter_text(float value) {
    return shortest_text(value, 9, [](const char *text) { return std::strtof(text, nullptr); });
}

std::string parameter_text(double value) {
    return shortest_text(value, 17, [](const char *text) { return std::strtod(text, nullptr); });
}

std::string parameter_text(long long value) {
    return std::to_string(value);
}

std::string parameter_text(bool value) {
    return value ? "true" : "false";
}

void throw_unknown_parameter(const std::string &owner, const std::vector<ParameterInfo> &infos,
                             const std::string &name) {
    ParameterSet(owner, infos).info(name);  // throws, naming the known ones
    throw Error("internal: parameter '" + name + "' of '" + owner + "' is and is not declared");
}

void throw_unnamed_choice(const std::string &name) {
    throw Error("internal: a value of parameter '" + name + "' has no name among its choices");
}

}  // namespace aaf
