#pragma once
// Builds the modules listed in `[Pipeline] modules = A, B, ...` (MRPT RTTI class names, namespace
// rpvio optional) and plays a rawlog through them, in time order, streaming.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "mrpt_modules/core/module.h"
#include "mrpt_modules/core/run_messages.h"

namespace rpvio {

class Pipeline {
 public:
  /// Throws InputError naming the config file (and line) for an unknown module, a bad option or
  /// a key no module reads. Modules log at `verbosity` and above; output modules write into
  /// `output_dir` (none when ""); the loop closure loads and saves `maps`.
  Pipeline(const std::string& config_path, const Calibration& calibration,
           mrpt::system::VerbosityLevel verbosity = mrpt::system::LVL_INFO,
           const std::string& output_dir = "", const MapFolders& maps = {});

  /// Streams the rawlog through the bus; `on_entry(entries_read)` after each observation; then
  /// finish(). Throws InputError on bad rawlog content (naming file and entry) without finishing:
  /// the caller decides what the frames before it are worth (finish({false, what})).
  void play(const std::string& rawlog_path, const std::function<void(size_t)>& on_entry = {});
  /// Publishes `end`, then calls every module's finish() in order (the output modules, listed
  /// after what they record, write then).
  void finish(const RunEnd& end = {});

  /// The sensor labels the modules consume that the rawlog has no observation of in its first
  /// `seconds` (a quick scan; bad input met there ends the scan, play() reports it).
  std::vector<std::string> missingSensors(const std::string& rawlog_path,
                                          double seconds = 10) const;

  PipelineContext& context() { return context_; }
  /// The configuration in effect: [Pipeline] and every module's options, all keys (INI text).
  std::string effectiveConfig() const;
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
