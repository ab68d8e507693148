#pragma once
// Writes a simulated sequence as a dataset (DESIGN.md §4): DIR/seq.rawlog (+ seq_Images/),
// DIR/groundtruth.tum (body pose at IMU rate), DIR/groundtruth_biases.csv (true IMU biases),
// DIR/calib.ini, DIR/dynamic_fraction.csv (per frame: the fraction of the image moving things
// cover) and DIR/sequence.json (what the sequence is). Every file appears complete or not at all.
#include <functional>
#include <string>

#include "sim/dynamic_coverage.h"
#include "sim/sim_config.h"

namespace rpvio::sim {

struct SequenceStats {
  size_t frames = 0, imu_samples = 0;
  double path_length = 0, max_speed = 0;
  std::vector<CoverageSample> dynamic_coverage;  // per frame, from the true (undegraded) mask
  CoverageSummary coverage;
};

/// `progress(frames_done, frames_total)` after each frame.
SequenceStats writeSequence(const SimConfig& config, const std::string& out_dir,
                            const std::function<void(size_t, size_t)>& progress = {});

/// Side-by-side PNG of the image and the colour-coded mask at IMU time t.
void writePreview(const SimConfig& config, double t, const std::string& png_path);

}  // namespace rpvio::sim
