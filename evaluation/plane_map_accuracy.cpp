#include "evaluation/plane_map_accuracy.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace rpvio::eval {
namespace {

/// The plane n·X = d of the estimate's world in the ground truth's: (R n)·X' = s d + (R n)·t.
std::pair<Eigen::Vector3d, double> inGroundTruth(const Plane& p, const Similarity& est_to_gt) {
  const Eigen::Vector3d n = est_to_gt.R * p.normal;
  return {n, est_to_gt.s * p.distance + n.dot(est_to_gt.t)};
}

/// The static true plane a discovered map plane stands for (see the header), or 0.
int nearestTruePlane(const Plane& p, const std::map<int, const Plane*>& true_of_label,
                     const Similarity& est_to_gt) {
  const auto [n, d] = inGroundTruth(p, est_to_gt);
  int best = 0;
  double best_offset = kDiscoveredMatchM;
  for (const auto& [id, truth] : true_of_label) {
    const double sign = n.dot(truth->normal) < 0 ? -1 : 1;
    const double angle = std::acos(std::clamp(sign * n.dot(truth->normal), -1.0, 1.0)) * 180 / M_PI;
    const double offset = std::abs(sign * d - truth->distance);
    if (angle <= kDiscoveredMatchDeg && offset < best_offset) best = id, best_offset = offset;
  }
  return best;
}

}  // namespace

PlaneMapAccuracy evaluatePlaneMap(const std::vector<Plane>& map, const std::vector<Plane>& truth,
                                  const Similarity& est_to_gt) {
  std::map<int, const Plane*> true_of_label;
  std::set<int> moving_labels;
  for (const Plane& p : truth) {
    if (p.moving)
      moving_labels.insert(p.id);
    else
      true_of_label[p.id] = &p;
  }
  PlaneMapAccuracy result;
  result.map_planes = map.size();
  std::map<int, std::vector<const Plane*>> entries;  // true id → its map planes
  for (const Plane& p : map) {
    std::vector<int> labels;
    for (int mask : p.mask_ids)
      if (true_of_label.count(mask)) labels.push_back(mask);
    if (p.discovered()) {
      ++result.discovered;
      if (const int id = nearestTruePlane(p, true_of_label, est_to_gt)) labels = {id};
    }
    const bool on_moving = std::any_of(p.mask_ids.begin(), p.mask_ids.end(),
                                       [&](int mask) { return moving_labels.count(mask) > 0; });
    if (labels.empty()) ++(on_moving ? result.on_moving : result.unmatched);
    if (labels.size() > 1) ++result.mixed;
    for (int label : labels) entries[label].push_back(&p);
  }
  for (const auto& [id, planes] : entries) {
    const Plane& true_plane = *true_of_label.at(id);
    TruePlaneAccuracy a;
    a.true_id = id;
    a.map_entries = planes.size();
    result.duplicates += planes.size() - 1;
    const Plane& best = **std::max_element(
        planes.begin(), planes.end(),
        [](const Plane* x, const Plane* y) { return x->observations < y->observations; });
    auto [n, d] = inGroundTruth(best, est_to_gt);
    if (n.dot(true_plane.normal) < 0) n = -n, d = -d;
    a.normal_error_deg = std::acos(std::clamp(n.dot(true_plane.normal), -1.0, 1.0)) * 180 / M_PI;
    a.distance_error_m = std::abs(d - true_plane.distance);
    a.normal_sigma_deg = std::sqrt(best.covariance.topLeftCorner<3, 3>().trace()) * 180 / M_PI;
    // ∂d'/∂(n, d) of d' = s d + (R n)·t.
    Eigen::Vector4d J;
    J << est_to_gt.R.transpose() * est_to_gt.t, est_to_gt.s;
    a.distance_sigma_m = std::sqrt(J.dot(best.covariance * J));
    double first = best.first_seen, last = best.last_seen;
    for (const Plane* p : planes)
      first = std::min(first, p->first_seen), last = std::max(last, p->last_seen);
    a.seen_s = last - first;
    result.planes.push_back(a);
  }
  return result;
}

}  // namespace rpvio::eval
