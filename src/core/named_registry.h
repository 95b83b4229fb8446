#pragma once
// Plug-ins by name (enhancement methods, procedures): the built-in ones, added when the registry
// is first used, and any a program registers. Safe to use from any thread and during static
// initialisation and destruction.

#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

namespace countershade {

template <typename Plugin>
class NamedRegistry {
 public:
  explicit NamedRegistry(std::vector<std::unique_ptr<const Plugin>> builtins)
      : plugins_(std::move(builtins)) {}

  // Adds a plug-in; a second one of the same name is a programming error.
  void add(std::unique_ptr<const Plugin> plugin, const char* kind) {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& p : plugins_)
      if (p->name() == plugin->name())
        throw std::logic_error(std::string(kind) + " '" + plugin->name() + "' is registered twice");
    plugins_.push_back(std::move(plugin));
  }
  // nullptr when none has that name.
  const Plugin* find(const std::string& name) {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& p : plugins_)
      if (p->name() == name) return p.get();
    return nullptr;
  }
  std::vector<std::string> names() {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<std::string> out;
    for (const auto& p : plugins_) out.push_back(p->name());
    return out;
  }
  const Plugin& first() {
    std::lock_guard<std::mutex> lock(mutex_);
    return *plugins_.front();
  }

 private:
  std::mutex mutex_;
  std::vector<std::unique_ptr<const Plugin>> plugins_;
};

}  // namespace countershade
