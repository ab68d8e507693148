#pragma once
// Pose and plane states of the sliding-window estimator.
#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <optional>

namespace rpvio {

struct StateEstimate {
  double t = 0;
  double pose[7] = {0, 0, 0, 0, 0, 0, 1};  // body in world [p, q]
  bool keyframe = false;
};

/// A plane n·X = d in the world frame (n on the unit sphere).
struct PlaneEstimate {
  double normal[3] = {0, 0, 1};
  double distance[1] = {0};
  uint64_t visit = 0;  // its stay in the window (PlaneObservation::visit)
  // Of (n, d), ambient (nothing along n itself), from the window's information when the plane
  // was last handed to the map; none before.
  std::optional<Eigen::Matrix4d> covariance;
};

using PlaneEstimates = std::map<int, PlaneEstimate>;

}  // namespace rpvio
