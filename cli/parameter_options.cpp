#include "parameter_options.h"

#include "aaf/core/methods/aaf/aaf_filter.h"
#include "aaf/core/util/error.h"
#include "commands.h"

namespace aaf::cli {

void add_parameter_option(CLI::App &cmd, const ParameterInfo &parameter, GivenParameters &given,
                          const std::string &help_text) {
    std::string help = help_text.empty() ? parameter.help : help_text;
    if (!parameter.unit.empty()) help += "; " + parameter.unit;
    if (parameter.type == ParameterType::Bool) {
        cmd.add_flag_callback(
            parameter.option_name(), [&given, name = parameter.name] { given[name] = "true"; }, help);
        return;
    }
    help += "; " + parameter.range_text();
    const char *type = parameter.type == ParameterType::Int     ? "INT"
                       : parameter.type == ParameterType::Float ? "FLOAT"
                                                                : "TEXT";
    cmd.add_option_function<std::string>(
           parameter.option_name(),
           [&given, name = parameter.name](const std::string &v) { given[name] = v; }, help)
        ->type_name(type)
        ->default_str(parameter.default_value);
}

void add_parameter_options(CLI::App &cmd, const std::vector<ParameterInfo> &parameters,
                           GivenParameters &given) {
    for (const ParameterInfo &parameter : parameters) add_parameter_option(cmd, parameter, given);
}

ParameterSet with_given(ParameterSet set, const GivenParameters &given) {
    for (const auto &entry : given) try {
            set.set(entry.first, entry.second);
        } catch (const Error &e) {
            // Named as typed (--mu), as CLI11 names the options it checks itself.
            throw UsageError(set.info(entry.first).option_name() + ": " + e.what());
        }
    return set;
}

void add_aaf_option(CLI::App &cmd, const std::string &name, GivenParameters &given, const std::string &help) {
    add_parameter_option(cmd, aaf_parameter_declarations().info(name), given, help);
}

AafParams aaf_params_given(const GivenParameters &given) {
    const ParameterDeclarations<AafParams> &aaf = aaf_parameter_declarations();
    return aaf.read(with_given(aaf.defaults(), given));
}

void add_adaptive_options(CLI::App &cmd, GivenParameters &plan, int &max_spp) {
    add_aaf_option(cmd, "mu", plan, "mu of the adaptive sampling rate (AAF Eq. 21)");
    cmd.add_option("--max-spp", max_spp, "Cap on the adaptive samples per pixel")->capture_default_str();
    const std::map<std::string, std::string> help = {
        {"light_bandlimit", "Light band-limit rule of the adaptive plan (the filter's --light-bandlimit)"},
        {"light_axes", "Light axes rule of the adaptive plan (the filter's --light-axes)"},
        {"pixel_footprint", "Pixel footprint of the adaptive plan (the filter's --pixel-footprint)"},
    };
    for (const std::string &name : aaf_plan_parameter_names())
        if (name != "mu") add_aaf_option(cmd, name, plan, help.count(name) ? help.at(name) : "");
}

std::vector<std::string> adaptive_option_names() {
    std::vector<std::string> names = {"--mu", "--max-spp"};
    for (const std::string &name : aaf_plan_parameter_names())
        if (name != "mu") names.push_back(aaf_parameter_declarations().info(name).option_name());
    return names;
}

std::string adaptive_parameters_text(const AafParams &plan, int max_spp) {
    const ParameterSet set = aaf_parameter_declarations().write(plan);
    std::string text = "mu=" + set.text("mu") + " max_spp=" + std::to_string(max_spp);
    for (const std::string &name : aaf_plan_parameter_names())
        if (name != "mu") text += " " + name + "=" + set.text(name);
    return text;
}

}  // namespace aaf::cli
