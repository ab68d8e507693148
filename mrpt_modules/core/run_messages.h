#pragma once
// What the modules publish about a run besides their results, for the output modules (run
// statistics, writers): per-frame timing and state, and the end of the run.
#include <string>

namespace rpvio {

/// Published by Pipeline::play before the first observation.
struct RunStart {};

/// Published by the front-end before each FeatureFrame: wall time spent reading and decoding the
/// image files (image and mask) since the previous frame.
struct FrameDecoding {
  double t = 0;  // image time (s)
  double load_ms = 0;
};

/// What the estimator did with one frame.
struct FrameReport {
  std::string state;  // "initializing", "tracking", "reset"
  double optimization_ms = 0;
  size_t features = 0;    // features in use in the newest frame
  size_t planes = 0;      // planes with homography factors
  int ground_plane = -1;  // the plane camera-height factors held the cameras over (−1: none)
  // The frame began with what the previous keyframe's long solve left: the planes' covariances
  // and the oldest keyframe's marginalization (max_iterations_before_deferring).
  bool finished_keyframe_work = false;
};

/// Published by the estimator for every frame it processed, in order (a frame waiting for its IMU
/// data is processed with a later one).
struct EstimatorFrame {
  double t = 0;  // IMU clock
  FrameReport report;
};

/// Published by Pipeline::finish before the modules finish: whether the rawlog was played to its
/// end, or ended in bad input (then the outputs hold the frames before it).
struct RunEnd {
  bool complete = true;
  std::string input_error;  // "" when complete
};

}  // namespace rpvio
