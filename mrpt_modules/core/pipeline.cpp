#include "mrpt_modules/core/pipeline.h"

#include <set>
#include <sstream>

#include "common/input_error.h"
#include "rawlog_io/rawlog_labels.h"
#include "rawlog_io/rawlog_reader.h"

namespace rpvio {

Pipeline::Pipeline(const std::string& config_path, const Calibration& calibration,
                   mrpt::system::VerbosityLevel verbosity, const std::string& output_dir,
                   const MapFolders& maps) {
  context_.calibration = calibration;
  context_.output_dir = output_dir;
  context_.maps = maps;
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
    module->setMinLoggingLevel(verbosity);
    module->initialize(ini, name, context_);
    modules_.push_back(module);
  }
  if (modules_.empty()) throw InputError(config_path, "[Pipeline]", "no modules listed");
  // Every key must have been read by a module: a misspelt key would otherwise be ignored.
  const auto unread = ini.unreadKeys();
  if (!unread.empty()) {
    const auto& k = unread.front();
    throw InputError(config_path, "line " + std::to_string(k.line),
                     "unknown key '" + k.key + "' in [" + k.section + "]" +
                         (ini.sectionAskedFor(k.section)
                              ? ""
                              : " (no module of [Pipeline] modules reads that section)"));
  }
}

std::string Pipeline::effectiveConfig() const {
  std::string text = "[Pipeline]\nmodules =";
  for (size_t k = 0; k < modules_.size(); ++k)
    text += (k ? ", " : " ") + modules_[k]->getLoggerName();
  text += "\n";
  for (const auto& m : modules_) text += "\n" + m->optionsText();
  return text;
}

std::vector<std::string> Pipeline::missingSensors(const std::string& rawlog_path,
                                                  double seconds) const {
  std::set<std::string> present;
  RawlogReader reader(rawlog_path);  // a missing or unreadable file is reported as such
  try {
    double first_t = -1;
    while (const auto obs = reader.next()) {
      const double t = toSeconds(obs->timestamp);
      if (first_t < 0) first_t = t;
      if (t > first_t + seconds) break;
      present.insert(obs->sensorLabel);
    }
  } catch (const InputError&) {
  }
  std::vector<std::string> missing;
  for (const char* label : {labels::kCamera, labels::kPlaneMask, labels::kImu})
    if (context_.bus.hasSensorSubscribers(label) && !present.count(label)) missing.push_back(label);
  return missing;
}

void Pipeline::play(const std::string& rawlog_path, const std::function<void(size_t)>& on_entry) {
  RawlogReader reader(rawlog_path);
  context_.bus.publish(RunStart{});
  while (auto obs = reader.next()) {
    context_.bus.publishObservation({obs, &reader});
    if (on_entry) on_entry(reader.entriesRead());
  }
  finish();
}

void Pipeline::finish(const RunEnd& end) {
  context_.bus.publish(end);
  for (auto& m : modules_) m->finish();
}

}  // namespace rpvio
