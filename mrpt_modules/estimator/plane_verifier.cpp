#include "mrpt_modules/estimator/plane_verifier.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace rpvio {
namespace {

/// A feature seen in both frames: its bearing in j turned into k's orientation, and in k.
struct BearingPair {
  Eigen::Vector3d rotated_j, k;
};

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

/// Rotation-compensated parallax of a pair, in the normalized image plane.
double parallax(const BearingPair& p) {
  return (p.rotated_j.hnormalized() - p.k.hnormalized()).norm();
}

/// Distance of b_k from the epipolar line of t through R_kj b_j (l = t × R_kj b_j), in the
/// normalized image plane.
double epipolarDistance(const BearingPair& p, const Eigen::Vector3d& t) {
  const Eigen::Vector3d line = t.cross(p.rotated_j);
  const double norm = line.head<2>().norm();
  return norm > 1e-12 ? std::abs(line.dot(p.k / p.k.z())) / norm : 0;
}

/// The translation direction that best satisfies tᵀ (R_kj b_j × b_k) = 0 for all pairs: the right
/// singular vector of the smallest singular value of the stacked, normalized constraints.
Eigen::Vector3d translationDirection(const std::vector<BearingPair>& pairs) {
  Eigen::MatrixX3d A(pairs.size(), 3);
  for (size_t i = 0; i < pairs.size(); ++i) {
    const Eigen::Vector3d row = pairs[i].rotated_j.cross(pairs[i].k);
    A.row(i) = row.norm() > 1e-12 ? Eigen::Vector3d(row / row.norm()) : row;
  }
  const Eigen::JacobiSVD<Eigen::MatrixX3d> svd(A, Eigen::ComputeFullV);
  return svd.matrixV().col(2);
}

}  // namespace

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
  if (!R_previous_current) history_.clear();
  const Eigen::Quaterniond orientation =
      history_.empty() ? Eigen::Quaterniond::Identity()
                       : (history_.back().orientation * *R_previous_current).normalized();
  // The newest past frame at least span_s older.
  const Past* reference = nullptr;
  for (auto it = history_.rbegin(); it != history_.rend() && !reference; ++it)
    if (frame.t - it->frame.t >= options_.span_s) reference = &*it;
  if (reference) {
    const Eigen::Matrix3d R_kj =
        (orientation.inverse() * reference->orientation).toRotationMatrix();
    const CheckResult result = check(reference->frame, frame, R_kj);  // rejected planes left out
    const double moving_px =
        std::max(options_.moving_px, options_.moving_noise_ratio * result.noise_px);
    for (const auto& [plane, error_px] : result.distance_px) {
      if (error_px < options_.static_px) {
        disagreements_[plane] = 0;
      } else if (error_px > moving_px && ++disagreements_[plane] >= options_.reject_after) {
        rejected_.insert(plane);
        rejections_.push_back({frame.t, plane, error_px});
      }
    }
  }
  history_.push_back({frame, orientation});
  // Older frames than the newest one at least span_s before this frame are not needed again.
  while (history_.size() > 2 && frame.t - history_[1].frame.t >= options_.span_s)
    history_.pop_front();

  FeatureFrame kept = frame;
  if (!rejected_.empty())
    kept.features.erase(
        std::remove_if(kept.features.begin(), kept.features.end(),
                       [&](const TrackedFeature& f) { return rejected_.count(f.plane_id) > 0; }),
        kept.features.end());
  return kept;
}

}  // namespace rpvio
