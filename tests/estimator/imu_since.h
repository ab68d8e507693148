#pragma once
// The IMU samples a frame brings to the bootstrapper: those of `imu` (time order) after the ones
// already handed out (`next`, advanced) up to and including time t.
#include <vector>

#include "common/sensor_types.h"

namespace rpvio::test {

inline std::vector<ImuSample> imuUpTo(const std::vector<ImuSample>& imu, size_t& next, double t) {
  std::vector<ImuSample> since_previous;
  for (; next < imu.size() && imu[next].t <= t; ++next) since_previous.push_back(imu[next]);
  return since_previous;
}

}  // namespace rpvio::test
