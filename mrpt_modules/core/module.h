#pragma once
// Base of the estimation modules (DESIGN.md §3). Modules are MRPT RTTI classes, built by class name
// from the `[Pipeline] modules = ...` list of an INI file; each reads its own `[ClassName]` section
// and connects to the others through the Bus.
#include <mrpt/rtti/CObject.h>
#include <mrpt/system/COutputLogger.h>
#include <string>

#include "mrpt_modules/core/bus.h"
#include "rawlog_io/calibration.h"
#include "rawlog_io/ini_file.h"

namespace rpvio {

/// What every module may use when it is set up.
struct PipelineContext {
  Calibration calibration;
  Bus bus;
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
};

}  // namespace rpvio
