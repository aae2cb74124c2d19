#pragma once

#include <memory>

#include "aaf/core/framework/method.h"

namespace aaf {

/// The built-in methods, each defined in its own folder; registered in registry.cpp.
std::unique_ptr<Method> make_aaf_method();
std::unique_ptr<Method> make_gaussian_method();
std::unique_ptr<Method> make_maaf_method();
std::unique_ptr<Method> make_isg_shadow_method();
std::unique_ptr<Method> make_isg_glossy_method();
std::unique_ptr<Method> make_isg_dof_method();
std::unique_ptr<Method> make_ratio_method();
std::unique_ptr<Method> make_maaf6_method();

}  // namespace aaf
