#pragma once

#include <memory>
#include <string>
#include <vector>

#include "aaf/core/framework/method.h"

namespace aaf {

/// Every registered method: the built-in ones (methods/registry.cpp) in
/// their order, then those registered with MethodRegistration.
const std::vector<const Method *> &methods();

/// The method called `name`; throws aaf::Error listing the known names.
const Method &find_method(const std::string &name);

/// Registers a method from outside the library (a plug-in, a test): one
/// line at namespace scope, `static const MethodRegistration r(std::make_unique<MyMethod>());`.
/// Throws aaf::Error (at start-up) when the name is taken or not lower-case [a-z0-9_-].
class MethodRegistration {
  public:
    explicit MethodRegistration(std::unique_ptr<Method> method);
};

}  // namespace aaf
