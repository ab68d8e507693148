#pragma once
#include <string>
#include <vector>

#include "evaluation/trajectory_metrics.h"

namespace rpvio::eval {

struct PlottedEstimate {
  std::string label;
  const EvalResult* result;  // aligned estimate + per-pair errors
};

/// PNG with the top view (x-y) and side view (x-z) of the ground truth and every aligned estimate,
/// and the translation error over time. Written to a temporary name, then renamed.
void writeTrajectoryPlot(const std::string& png_path, const Trajectory& gt,
                         const std::vector<PlottedEstimate>& estimates, const std::string& title);

}  // namespace rpvio::eval
