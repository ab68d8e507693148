#pragma once
// Converts an EuRoC (ASL folder) sequence into an rpvio rawlog + calib.ini (DESIGN.md §4):
// `mav0/cam0` images → CAM0, `mav0/imu0/data.csv` → IMU, optional masks folder (PNG named like the
// images) → PLANE_MASK, optional ground truth (TUM or EuRoC CSV) → GROUND_TRUTH.
#include <functional>
#include <string>

#include "common/sensor_types.h"

namespace rpvio {

struct EurocImportOptions {
  std::string mav0_dir;
  std::string groundtruth_file;  // optional
  std::string masks_dir;         // optional
  std::string output_rawlog;     // calib.ini is written beside it
};

struct EurocImportCounts {
  size_t images = 0, masks = 0, imu = 0, groundtruth = 0;
};

/// Sensor calibration from `mav0/cam0/sensor.yaml` and `mav0/imu0/sensor.yaml`.
Calibration readEurocCalibration(const std::string& mav0_dir);

/// Throws InputError (file + line/entry) on bad input; nothing appears under the output names
/// unless the import completes. `progress(done, total)` is called now and then.
EurocImportCounts importEuroc(const EurocImportOptions& options,
                              const std::function<void(size_t, size_t)>& progress = {});

}  // namespace rpvio
