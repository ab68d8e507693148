#pragma once
// Absolute trajectory error (after alignment), relative pose error and coverage of an estimate
// against ground truth (Sturm et al. 2012; Zhang & Scaramuzza 2018).
#include <string>

#include "common/sensor_types.h"
#include "evaluation/alignment.h"
#include "evaluation/association.h"
#include "evaluation/error_stats.h"

namespace rpvio::eval {

struct EvalOptions {
  AlignMode align = AlignMode::SE3;
  double max_dt = 0.01;  // association window (s)
  bool associate_by_index = false;
  double rpe_distance = 10.0;  // metres travelled between the two poses of an RPE pair
  int rpe_frames = 1;          // frame delta of the second RPE
};

struct RelativeError {
  ErrorStats translation;   // m
  ErrorStats rotation_deg;  // deg
};

struct EvalResult {
  Association pairs;
  Similarity alignment;
  ErrorStats ate;  // translation, m
  double ate_rotation_rmse_deg = 0;
  RelativeError rpe_distance, rpe_frames;
  double coverage = 0;          // fraction of the ground-truth duration the estimate spans
  std::vector<double> times;    // per pair: estimate time
  std::vector<double> errors;   // per pair: translation error after alignment (m)
  Trajectory aligned_estimate;  // every estimate pose moved by the alignment
};

/// Throws std::runtime_error when fewer than 3 pairs associate.
EvalResult evaluate(const Trajectory& gt, const Trajectory& est, const EvalOptions& options);

}  // namespace rpvio::eval
