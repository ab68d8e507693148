#pragma once
// Planes other than the initialization plane (RP-VIO): once the camera motion between frames i
// and j is metric, a plane's homography between the same frames, decomposed into (R, t/d, n),
// gives its distance from the ratio of the metric translation to the decomposed one.
#include <optional>
#include <string>
#include <vector>

#include "mrpt_modules/initialization/plane_motion_from_homography.h"

namespace rpvio {

/// A plane n·X = d in camera i (n unit, d > 0 in metres).
struct CameraPlane {
  Eigen::Vector3d n;
  double d;
};

/// d = argmin ‖t − d m‖ = t·m / ‖m‖² over the decomposition (m = t/d) whose rotation is closest to
/// the metric R and whose t/d points along t. `R`, `t`: X_j = R X_i + t, metric.
std::optional<CameraPlane> planeFromMetricMotion(const std::vector<Eigen::Vector2d>& points_i,
                                                 const std::vector<Eigen::Vector2d>& points_j,
                                                 const Eigen::Matrix3d& R, const Eigen::Vector3d& t,
                                                 const HomographyInitOptions& options,
                                                 std::string* why_not = nullptr);

}  // namespace rpvio
