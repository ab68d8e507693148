#pragma once
// Writes a simulated sequence as a dataset (DESIGN.md §4): DIR/seq.rawlog (+ seq_Images/),
// DIR/groundtruth.tum (body pose at IMU rate), DIR/groundtruth_biases.csv (true IMU biases),
// DIR/calib.ini. Every file appears complete or not at all.
#include <functional>
#include <string>

#include "sim/sim_config.h"

namespace rpvio::sim {

struct SequenceStats {
  size_t frames = 0, imu_samples = 0;
  double path_length = 0, max_speed = 0;
  double character_pixel_fraction = 0;  // mean fraction of the image covered by characters
};

/// `progress(frames_done, frames_total)` after each frame.
SequenceStats writeSequence(const SimConfig& config, const std::string& out_dir,
                            const std::function<void(size_t, size_t)>& progress = {});

/// Side-by-side PNG of the image and the colour-coded mask at IMU time t.
void writePreview(const SimConfig& config, double t, const std::string& png_path);

}  // namespace rpvio::sim
