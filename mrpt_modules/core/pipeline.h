#pragma once
// Builds the modules listed in `[Pipeline] modules = A, B, ...` (MRPT RTTI class names, namespace
// rpvio optional) and plays a rawlog through them, in time order, streaming.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "mrpt_modules/core/module.h"

namespace rpvio {

class Pipeline {
 public:
  /// Throws InputError naming the config file for an unknown module or a bad option.
  Pipeline(const std::string& config_path, const Calibration& calibration);

  /// Streams the rawlog through the bus; `on_entry(entries_read)` after each observation.
  /// Throws InputError on bad rawlog content (naming file and entry).
  void play(const std::string& rawlog_path, const std::function<void(size_t)>& on_entry = {});

  PipelineContext& context() { return context_; }
  const std::vector<std::shared_ptr<Module>>& modules() const { return modules_; }
  /// The module of the given class, or nullptr.
  template <typename M>
  std::shared_ptr<M> find() const {
    for (const auto& m : modules_)
      if (auto typed = std::dynamic_pointer_cast<M>(m)) return typed;
    return nullptr;
  }

 private:
  PipelineContext context_;
  std::vector<std::shared_ptr<Module>> modules_;
};

}  // namespace rpvio
