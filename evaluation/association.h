#pragma once
// Pairs of (ground-truth index, estimate index) compared by the metrics.
#include <utility>
#include <vector>

#include "common/sensor_types.h"

namespace rpvio::eval {

using Association = std::vector<std::pair<size_t, size_t>>;

/// Each estimate pose paired with the ground-truth pose nearest in time, when within `max_dt`;
/// each ground-truth pose used at most once. Both trajectories must be sorted by time. O(n + m).
Association associateByTime(const Trajectory& gt, const Trajectory& est, double max_dt);
/// Pairs i ↔ i over the common length (KITTI files carry no timestamps).
Association associateByIndex(const Trajectory& gt, const Trajectory& est);

}  // namespace rpvio::eval
