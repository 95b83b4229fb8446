#pragma once
// Parts of the program kept in shared libraries of their own and loaded when first needed, so that
// a command pays only for the libraries it uses (codecs/image_codec.h says why). Each is
// libcountershade_NAME.so, found beside the running program or in ../lib/countershade from it,
// and gives one object through its C entry point `countershade_NAME`. A library whose
// `countershade_plugin_interface` differs from the program's (a stamp of codecs/*.h, set by the
// build) is refused, and the next place tried.

#include <string>

namespace countershade {

// Loads the library once (safe from any thread) and returns its object. Throws
// std::runtime_error naming the places tried when it cannot be loaded.
void* plugin_object(const std::string& name);

template <typename T>
const T& plugin(const std::string& name) {
  return *static_cast<const T*>(plugin_object(name));
}

}  // namespace countershade
