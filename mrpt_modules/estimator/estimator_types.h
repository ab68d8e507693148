#pragma once
// Plane states of the sliding-window estimator.
#include <cstdint>
#include <map>

namespace rpvio {

/// A plane n·X = d in the world frame (n on the unit sphere).
struct PlaneEstimate {
  double normal[3] = {0, 0, 1};
  double distance[1] = {0};
  uint64_t visit = 0;  // its stay in the window (PlaneObservation::visit)
};

using PlaneEstimates = std::map<int, PlaneEstimate>;

}  // namespace rpvio
