#include "evaluation/plane_map_accuracy.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace rpvio::eval {

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
    // n·X = d in the estimate's world → (R n)·X' = s d + (R n)·t in the ground truth's.
    Eigen::Vector3d n = est_to_gt.R * best.normal;
    double d = est_to_gt.s * best.distance + n.dot(est_to_gt.t);
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
