#pragma once
// Writes an rpvio rawlog as an EuRoC (ASL) folder, so that other systems run on the same data:
// OUT/mav0/cam0 (data/<ns>.png, data.csv, sensor.yaml), OUT/mav0/imu0 (data.csv, sensor.yaml),
// OUT/mav0/state_groundtruth_estimate0/data.csv when the rawlog has ground truth (velocity by
// central differences, biases 0: a rawlog has none), and the plane masks as OUT/masks/<ns>.png
// (the layout `rpvio-import euroc --masks` reads; no masks folder when the rawlog has none).
// Camera stamps are moved onto the IMU clock by calib.ini's time offset (EuRoC has none). Every
// number with all its digits.
#include <functional>
#include <string>

namespace rpvio {

struct EurocExportCounts {
  size_t images = 0, masks = 0, imu = 0, groundtruth = 0;
};

/// The calibration is the calib.ini beside the rawlog. Throws InputError on bad input or when
/// `out_dir` exists; nothing appears under `out_dir` unless the export completes.
EurocExportCounts exportEuroc(const std::string& rawlog_path, const std::string& out_dir,
                              const std::function<void(size_t)>& progress = {});

}  // namespace rpvio
