#pragma once
// States shared by the planar initializer and the sliding-window estimator.
#include <Eigen/Geometry>
#include <map>
#include <memory>

#include "mrpt_modules/core/feature_frame.h"
#include "mrpt_modules/imu/imu_preintegration.h"

namespace rpvio {

/// One frame as the estimator keeps it: features, IMU since the previous kept frame, state.
struct WindowFrame {
  FeatureFrame features;
  std::shared_ptr<ImuPreintegration> imu_from_previous;  // null for the first frame
  double pose[7] = {0, 0, 0, 0, 0, 0, 1};                // body in world [p, q]
  double speed_bias[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};    // [v, ba, bg]
};

/// A plane n·X = d in the world frame (n on the unit sphere).
struct PlaneEstimate {
  double normal[3] = {0, 0, 1};
  double distance[1] = {0};
};

using PlaneEstimates = std::map<int, PlaneEstimate>;

}  // namespace rpvio
