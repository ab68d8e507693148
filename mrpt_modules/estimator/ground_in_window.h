#pragma once
// Which of the window's planes is the ground a camera of known height stands over (calib.ini
// [ground] camera_height), for the camera-height factor (camera_height_factor.h).
#include <Eigen/Core>
#include <optional>
#include <set>

#include "mrpt_modules/estimator/estimator_types.h"

namespace rpvio {

struct GroundInWindow {
  int plane = -1;
  double side = 1;  // sign of n·c − d for the cameras above it
};

/// Among `candidates` of `planes` (world frame, z up): the plane whose normal is within
/// `max_tilt_deg` of the vertical, that lies below `camera_centre` and whose distance from it is
/// nearest to `height`, if within `max_relative_error` of it (a table top is not the floor).
std::optional<GroundInWindow> groundInWindow(const PlaneEstimates& planes,
                                             const std::set<int>& candidates,
                                             const Eigen::Vector3d& camera_centre, double height,
                                             double max_tilt_deg, double max_relative_error = 0.3);

}  // namespace rpvio
