#pragma once
// Pose and plane states of the sliding-window estimator, and what it publishes.
#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

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

/// A mask plane found moving against the camera's motion and excluded (plane_verifier.h).
struct PlaneRejection {
  double t = 0;  // frame time (IMU clock)
  int plane_id = 0;
  double error_px = 0;  // median epipolar distance at the deciding check
};

/// A discovered plane accepted as static, or rejected as moving (plane_discovery.h).
struct PlaneDiscoveryEvent {
  double t = 0;  // frame time (IMU clock)
  int plane_id = 0;
  bool accepted = true;  // false: rejected as moving
};

struct ResetEvent {
  double t = 0;
  std::string cause;
};

/// Published by the estimator module when the run ends (after its window went to the map).
struct EstimatorSummary {
  // The frame on which the estimator initialized, -1 if never (a late initialization's first pose
  // is earlier: Bootstrapper, undecided time offset).
  double initialized_at = -1;
  double time_offset_s = 0;
  std::string time_offset_note;
  std::vector<ResetEvent> resets;
  std::string status;  // the last status with its figures (why it is not tracking)
  std::vector<PlaneRejection> rejected_planes;   // mask planes found moving (plane_verifier.h)
  size_t planes_discovered = 0;                  // candidate planes (rpvio-auto)
  std::vector<PlaneDiscoveryEvent> discoveries;  // ... accepted as static or rejected as moving
};

}  // namespace rpvio
