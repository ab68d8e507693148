#pragma once
// Base of the estimation modules (DESIGN.md §3). Modules are MRPT RTTI classes, built by class name
// from the `[Pipeline] modules = ...` list of an INI file; each reads its own `[ClassName]` section
// and connects to the others through the Bus.
#include <mrpt/rtti/CObject.h>
#include <mrpt/system/COutputLogger.h>
#include <string>
#include <utility>

#include "common/ini_file.h"
#include "common/sensor_types.h"
#include "mrpt_modules/core/bus.h"

namespace rpvio {

/// What every module may use when it is set up.
/// A saved map to start from and where to save the run's (rpvio-slam --map, --save-map).
struct MapFolders {
  std::string load;  // "" = none
  std::string save;  // "" = not saved
};

struct PipelineContext {
  Calibration calibration;
  Bus bus;
  std::string output_dir;  // where output modules write; "" = nowhere (they write nothing)
  MapFolders maps;
};

class Module : public mrpt::rtti::CObject, public mrpt::system::COutputLogger {
  DEFINE_VIRTUAL_MRPT_OBJECT(Module)

 public:
  /// Reads the options of `section` (InputError naming the file/line on a bad value) and subscribes
  /// to what the module consumes.
  virtual void initialize(const IniFile& config, const std::string& section,
                          PipelineContext& context) = 0;
  /// Called once after the last observation (flush, final outputs).
  virtual void finish() {}
  /// The options the module runs with, as INI text with its section header(s): every key, loaded
  /// or default (rpvio-slam writes them to OUT/config_used.ini).
  const std::string& optionsText() const { return options_text_; }

 protected:
  /// Records the module's effective options (`[section]` + describeOptions) and logs them.
  void setOptionsText(std::string text) {
    options_text_ = std::move(text);
    MRPT_LOG_INFO_STREAM("options:\n" << options_text_);
  }

 private:
  std::string options_text_;
};

}  // namespace rpvio
