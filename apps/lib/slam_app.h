#pragma once
// rpvio-slam: plays a rawlog through the modules of a mode's config. The modules write the outputs
// (trajectory, statistics, plane map: the output modules listed in the config); the app checks the
// inputs and the output folder first, shows progress and applies the bad-input policy.
#include <optional>
#include <string>

#include "common/input_error.h"

namespace rpvio::apps {

struct SlamAppOptions {
  std::string config, calib, rawlog, out;
  std::string map;        // a folder --save-map wrote: relocalize in it ("" = none)
  std::string save_map;   // a folder to save the run's map in ("" = not saved)
  bool quiet = false;     // modules log warnings only, no progress line
  bool progress = false;  // a progress line on stderr (a terminal)
};

struct SlamAppResult {
  size_t frames = 0;  // frames the front-end published
  size_t poses = 0;   // state estimates
  size_t resets = 0;
  double wall_s = 0;
  std::string status;                     // the estimator's last status ("" without an estimator)
  std::optional<InputError> input_error;  // none when the rawlog was played to its end
};

/// Builds the pipeline (InputError on a bad config, calibration, a rawlog without what the modules
/// consume, or an output folder that cannot be written), plays the rawlog and finishes the run.
/// Bad input part-way through the rawlog ends the run there: the outputs are written for the
/// frames before it and `input_error` is the error (it is thrown when no frame was processed).
SlamAppResult runSlam(const SlamAppOptions& options);

int slamMain(int argc, char** argv);

}  // namespace rpvio::apps
