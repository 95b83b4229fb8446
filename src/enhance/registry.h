#pragma once
// The methods by name: the built-in ones (listed in registry.cpp) and any a program adds.

#include <memory>
#include <string>
#include <vector>

#include "enhance/method.h"

namespace countershade {

// nullptr when no method has that name.
const EnhancementMethod* find_method(const std::string& name);
// The method of that name; InputError listing the known methods when there is none.
const EnhancementMethod& method_named(const std::string& name, const std::string& where);
std::vector<std::string> method_names();
// The method whose output is the unenhanced rendering (a scene's reference image).
const EnhancementMethod& unenhanced_method();

// Adds a method (a test's, a lab's own); its name must be new. The registration line of a method
// outside this library is one static MethodRegistration.
void register_method(std::unique_ptr<const EnhancementMethod> method);
struct MethodRegistration {
  explicit MethodRegistration(std::unique_ptr<const EnhancementMethod> method) {
    register_method(std::move(method));
  }
};

}  // namespace countershade
