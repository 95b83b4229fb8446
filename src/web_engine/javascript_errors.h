#pragma once
// How the engine's bindings report bad input: as a JavaScript Error with the C++ message, which
// the page can show, instead of an exception pointer the page cannot read.

#include <emscripten/val.h>

#include <cstdlib>
#include <exception>
#include <string>

namespace countershade::web_engine {

// Runs f; an exception it throws reaches JavaScript as an Error with the same message.
template <class F>
auto errors_to_javascript(F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const std::exception& e) {
    emscripten::val::global("Error").new_(std::string(e.what())).throw_();
    std::abort();  // throw_ does not return
  }
}

}  // namespace countershade::web_engine
