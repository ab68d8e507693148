#include "mrpt_modules/core/pipeline.h"

#include <sstream>

#include "rawlog_io/input_error.h"
#include "rawlog_io/rawlog_reader.h"

namespace rpvio {

Pipeline::Pipeline(const std::string& config_path, const Calibration& calibration) {
  context_.calibration = calibration;
  const IniFile ini(config_path);
  std::string list = ini.text("Pipeline", "modules");
  for (char& c : list)
    if (c == ',') c = ' ';
  std::istringstream names(list);
  for (std::string name; names >> name;) {
    const std::string qualified = name.find("::") == std::string::npos ? "rpvio::" + name : name;
    auto module = std::dynamic_pointer_cast<Module>(mrpt::rtti::classFactory(qualified));
    if (!module)
      throw InputError(config_path, "line " + std::to_string(ini.line("Pipeline", "modules")),
                       "unknown module '" + name + "' (not a registered rpvio::Module)");
    module->setLoggerName(name);
    module->initialize(ini, name, context_);
    modules_.push_back(module);
  }
  if (modules_.empty()) throw InputError(config_path, "[Pipeline]", "no modules listed");
}

void Pipeline::play(const std::string& rawlog_path, const std::function<void(size_t)>& on_entry) {
  RawlogReader reader(rawlog_path);
  while (auto obs = reader.next()) {
    context_.bus.publishObservation({obs, &reader});
    if (on_entry) on_entry(reader.entriesRead());
  }
  for (auto& m : modules_) m->finish();
}

}  // namespace rpvio
