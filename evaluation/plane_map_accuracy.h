#pragma once
// Accuracy of an estimated plane map against the true planes (issue 8): map planes are matched to
// true planes by the mask labels they were seen as (the simulator's mask label is the true plane's
// id), moved into the ground-truth frame by the trajectory's alignment, and compared: normal angle,
// offset, and how many map entries each true plane got (more than one: a duplicate).
#include <vector>

#include "evaluation/alignment.h"
#include "planes_map/plane.h"

namespace rpvio::eval {

struct TruePlaneAccuracy {
  int true_id = 0;
  size_t map_entries = 0;       // map planes seen as this label (1 is right)
  double normal_error_deg = 0;  // of its most observed map plane, after alignment
  double distance_error_m = 0;  // |d| difference of that plane, after alignment
  double seen_s = 0;            // last − first seen over its map planes
  // What that plane's covariance claims for the same two errors (standard deviations; the normal's
  // over both tilt directions).
  double normal_sigma_deg = 0;
  double distance_sigma_m = 0;
};

struct PlaneMapAccuracy {
  std::vector<TruePlaneAccuracy> planes;  // true planes in the map, by id
  size_t map_planes = 0;                  // entries in the map
  size_t duplicates = 0;                  // Σ (map_entries − 1)
  size_t mixed = 0;       // map planes seen as labels of several true planes (wrong merges)
  size_t unmatched = 0;   // map planes whose labels are no true plane
  size_t on_moving = 0;   // map planes seen only as labels of moving planes (not scored)
  size_t discovered = 0;  // map planes of the plane discovery (rpvio-auto), matched by geometry
};

/// `map` in the estimate's world, `truth` (id = label) in the ground-truth world; `est_to_gt` the
/// trajectory alignment (X_gt = s R X_est + t). Moving true planes (moving objects' faces) are no
/// static planes to score: a map plane seen only as their labels counts in `on_moving`. A
/// discovered map plane (no mask label) stands for the static true plane nearest to it once
/// aligned: normal within kDiscoveredMatchDeg, offset within kDiscoveredMatchM (the smallest
/// offset among those), else it is unmatched.
constexpr double kDiscoveredMatchDeg = 10, kDiscoveredMatchM = 0.3;
PlaneMapAccuracy evaluatePlaneMap(const std::vector<Plane>& map, const std::vector<Plane>& truth,
                                  const Similarity& est_to_gt);

}  // namespace rpvio::eval
