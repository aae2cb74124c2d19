#pragma once

// Each built-in method's ParameterDeclarations::defaults_read_back_differently(),
// for the test that every declared default reads back as its settings
// struct's default member initialiser.
#include <string>
#include <utility>
#include <vector>

namespace aaf {

std::vector<std::string> aaf_parameter_defaults_read_back_differently();
std::vector<std::string> gaussian_parameter_defaults_read_back_differently();
std::vector<std::string> maaf_parameter_defaults_read_back_differently();
std::vector<std::string> maaf6_parameter_defaults_read_back_differently();
std::vector<std::string> ratio_parameter_defaults_read_back_differently();
std::vector<std::string> isg_shadow_parameter_defaults_read_back_differently();
std::vector<std::string> isg_glossy_parameter_defaults_read_back_differently();
std::vector<std::string> isg_dof_parameter_defaults_read_back_differently();

/// (method name, the parameters whose default does not read back) per built-in method.
inline std::vector<std::pair<std::string, std::vector<std::string>>>
builtin_parameter_defaults_read_back_differently() {
    return {
        {"aaf", aaf_parameter_defaults_read_back_differently()},
        {"gaussian", gaussian_parameter_defaults_read_back_differently()},
        {"maaf", maaf_parameter_defaults_read_back_differently()},
        {"isg-shadow", isg_shadow_parameter_defaults_read_back_differently()},
        {"isg-glossy", isg_glossy_parameter_defaults_read_back_differently()},
        {"isg-dof", isg_dof_parameter_defaults_read_back_differently()},
        {"ratio", ratio_parameter_defaults_read_back_differently()},
        {"maaf6", maaf6_parameter_defaults_read_back_differently()},
    };
}

}  // namespace aaf
