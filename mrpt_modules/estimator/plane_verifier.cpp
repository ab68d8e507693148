#include "mrpt_modules/estimator/plane_verifier.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace rpvio {

PlaneVerifier::CheckResult PlaneVerifier::check(const FeatureFrame& j, const FeatureFrame& k,
                                                const Eigen::Matrix3d& R_kj) const {
  std::unordered_map<int, const TrackedFeature*> in_j;
  for (const TrackedFeature& f : j.features) in_j[f.id] = &f;
  std::map<int, std::vector<BearingPair>> by_plane;
  for (const TrackedFeature& f : k.features) {
    const auto it = in_j.find(f.id);
    if (f.plane_id <= 0 || rejected_.count(f.plane_id) || it == in_j.end() ||
        it->second->plane_id != f.plane_id)
      continue;
    by_plane[f.plane_id].push_back(
        {R_kj * it->second->normalized.homogeneous(), f.normalized.homogeneous()});
  }
  // The planes that can be judged, each with the translation its own features imply.
  struct Judged {
    int plane;
    const std::vector<BearingPair>* pairs;
    Eigen::Vector3d t;
  };
  std::vector<Judged> judged;
  size_t total = 0;
  for (const auto& [plane, pairs] : by_plane) {
    if (pairs.size() < options_.min_features) continue;
    std::vector<double> flow;
    for (const BearingPair& p : pairs) flow.push_back(parallax(p));
    if (median(flow) * options_.focal_px < options_.min_parallax_px) continue;
    judged.push_back({plane, &pairs, translationDirection(pairs)});
    total += pairs.size();
  }
  if (judged.size() < 2) return {};  // nothing to compare with
  // The proposal of least truncated squared epipolar distance over all judged features (MSAC:
  // near planes, with large parallax, tell directions apart; far ones fit any nearby direction).
  const double limit = options_.moving_px / options_.focal_px;
  const double static_limit = options_.static_px / options_.focal_px;
  double best_cost = INFINITY;
  Eigen::Vector3d best_t = judged.front().t;
  for (const Judged& candidate : judged) {
    double cost = 0;
    for (const Judged& q : judged)
      for (const BearingPair& p : *q.pairs)
        cost += std::min(std::pow(epipolarDistance(p, candidate.t), 2), limit * limit);
    if (cost < best_cost) {
      best_cost = cost;
      best_t = candidate.t;
    }
  }
  // A verdict only when most features agree with it; their median distance is the check's noise.
  CheckResult result;
  std::vector<double> all;
  for (const Judged& q : judged) {
    std::vector<double> distances;
    for (const BearingPair& p : *q.pairs) distances.push_back(epipolarDistance(p, best_t));
    all.insert(all.end(), distances.begin(), distances.end());
    result.distance_px[q.plane] = median(distances) * options_.focal_px;
  }
  const size_t agreeing =
      std::count_if(all.begin(), all.end(), [&](double d) { return d < static_limit; });
  if (2 * agreeing <= total) return {};
  result.noise_px = median(all) * options_.focal_px;
  return result;
}

FeatureFrame PlaneVerifier::filter(const FeatureFrame& frame,
                                   const std::optional<Eigen::Quaterniond>& R_previous_current) {
  if (!options_.enabled) return frame;
  history_.push(frame, R_previous_current);
  if (const auto* reference = history_.reference(options_.span_s)) {
    // Rejected planes are left out of the check.
    const CheckResult result = check(reference->frame, frame, history_.rotationFrom(*reference));
    const double moving_px =
        std::max(options_.moving_px, options_.moving_noise_ratio * result.noise_px);
    for (const auto& [plane, error_px] : result.distance_px) {
      if (error_px < options_.static_px) {
        disagreements_[plane] = 0;
        judged_static_.insert(plane);
      } else if (error_px > moving_px && ++disagreements_[plane] >= options_.reject_after) {
        rejected_.insert(plane);
        judged_static_.erase(plane);
        rejections_.push_back({frame.t, plane, error_px});
      }
    }
  }
  history_.trim(options_.span_s);
  return withoutRejected(frame);
}

FeatureFrame PlaneVerifier::withoutRejected(const FeatureFrame& frame) const {
  FeatureFrame kept = frame;
  if (!rejected_.empty())
    kept.features.erase(
        std::remove_if(kept.features.begin(), kept.features.end(),
                       [&](const TrackedFeature& f) { return rejected_.count(f.plane_id) > 0; }),
        kept.features.end());
  return kept;
}

}  // namespace rpvio
