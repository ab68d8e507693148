#include "mrpt_modules/estimator/two_view_bearings.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

namespace rpvio {

std::vector<BearingPair> bearingPairs(const FeatureFrame& j, const FeatureFrame& k,
                                      const Eigen::Matrix3d& R_kj, std::vector<int>* ids) {
  std::unordered_map<int, const TrackedFeature*> in_j;
  for (const TrackedFeature& f : j.features) in_j[f.id] = &f;
  std::vector<BearingPair> pairs;
  for (const TrackedFeature& f : k.features) {
    const auto it = in_j.find(f.id);
    if (it == in_j.end()) continue;
    pairs.push_back({R_kj * it->second->normalized.homogeneous(), f.normalized.homogeneous()});
    if (ids) ids->push_back(f.id);
  }
  return pairs;
}

double parallax(const BearingPair& p) {
  return (p.rotated_j.hnormalized() - p.k.hnormalized()).norm();
}

double epipolarDistance(const BearingPair& p, const Eigen::Vector3d& t) {
  const Eigen::Vector3d line = t.cross(p.rotated_j);
  const double norm = line.head<2>().norm();
  return norm > 1e-12 ? std::abs(line.dot(p.k / p.k.z())) / norm : 0;
}

Eigen::Vector3d translationDirection(const std::vector<BearingPair>& pairs) {
  Eigen::MatrixX3d A(pairs.size(), 3);
  for (size_t i = 0; i < pairs.size(); ++i) {
    const Eigen::Vector3d row = pairs[i].rotated_j.cross(pairs[i].k);
    A.row(i) = row.norm() > 1e-12 ? Eigen::Vector3d(row / row.norm()) : row;
  }
  const Eigen::JacobiSVD<Eigen::MatrixX3d> svd(A, Eigen::ComputeFullV);
  return svd.matrixV().col(2);
}

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

void RotatedFrameHistory::push(const FeatureFrame& frame,
                               const std::optional<Eigen::Quaterniond>& R_previous_current) {
  if (!R_previous_current) frames_.clear();
  const Eigen::Quaterniond orientation =
      frames_.empty() ? Eigen::Quaterniond::Identity()
                      : (frames_.back().orientation * *R_previous_current).normalized();
  frames_.push_back({frame, orientation});
}

const RotatedFrameHistory::Past* RotatedFrameHistory::reference(double span_s) const {
  if (frames_.empty()) return nullptr;
  const double t = frames_.back().frame.t;
  for (auto it = frames_.rbegin(); it != frames_.rend(); ++it)
    if (t - it->frame.t >= span_s) return &*it;
  return nullptr;
}

Eigen::Matrix3d RotatedFrameHistory::rotationFrom(const Past& j) const {
  return (frames_.back().orientation.inverse() * j.orientation).toRotationMatrix();
}

void RotatedFrameHistory::trim(double span_s) {
  // Older frames than the newest one at least span_s before the newest are not needed again.
  while (frames_.size() > 2 && frames_.back().frame.t - frames_[1].frame.t >= span_s)
    frames_.pop_front();
}

}  // namespace rpvio
