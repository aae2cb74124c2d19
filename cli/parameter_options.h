#pragma once

// Command-line options generated from declared parameters (parameters.h):
// `aaf filter METHOD`'s, and those `aaf plan` and `render --adaptive` take
// from AAF's declarations, so the plan and the filter share one spelling,
// one range and one default.
#include <map>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "aaf/core/framework/parameters.h"
#include "aaf/core/methods/aaf/aaf_params.h"

namespace aaf::cli {

/// The text given on the command line per parameter name.
using GivenParameters = std::map<std::string, std::string>;

/// The option of one parameter: --with-dashes, a flag for a Bool, typed and
/// with its default otherwise; its help `help` (the declaration's when
/// empty), the unit and the valid values. What is given lands in `given`.
void add_parameter_option(CLI::App &cmd, const ParameterInfo &parameter, GivenParameters &given,
                          const std::string &help = "");
/// add_parameter_option() for each parameter, in order.
void add_parameter_options(CLI::App &cmd, const std::vector<ParameterInfo> &parameters,
                           GivenParameters &given);

/// `set` with each given value set; a bad one is a usage error naming the
/// option as typed (`--mu: method 'aaf': parameter 'mu' must be in > 0, got 0`).
ParameterSet with_given(ParameterSet set, const GivenParameters &given);

/// The option of AAF's parameter `name` (aaf_parameter_declarations()), with `help`.
void add_aaf_option(CLI::App &cmd, const std::string &name, GivenParameters &given,
                    const std::string &help = "");
/// AafParams{} with the AAF parameters given; a bad value is a usage error.
AafParams aaf_params_given(const GivenParameters &given);

/// `render --adaptive`'s options: --mu, --max-spp and the other parameters
/// the plan shares with the filter (aaf_plan_parameter_names()).
void add_adaptive_options(CLI::App &cmd, GivenParameters &plan, int &max_spp);
/// The options of add_adaptive_options(), "--mu" first.
std::vector<std::string> adaptive_option_names();
/// The plan's settings for a render's provenance, named as AAF declares them:
/// "mu=2 max_spp=100 light_bandlimit=sigma light_axes=per_axis pixel_footprint=receiver".
std::string adaptive_parameters_text(const AafParams &plan, int max_spp);

}  // namespace aaf::cli
