#include "evaluation/trajectory_metrics.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rpvio::eval {
namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

Eigen::Isometry3d toIsometry(const StampedPose& p) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = p.q.normalized().toRotationMatrix();
  T.translation() = p.p;
  return T;
}

double rotationAngleDeg(const Eigen::Matrix3d& R) {
  return Eigen::AngleAxisd(R).angle() * kRadToDeg;
}

/// RPE over pairs (i, j(i)) of associated poses: E = (G_i⁻¹ G_j)⁻¹ (A_i⁻¹ A_j).
RelativeError relativeError(const std::vector<Eigen::Isometry3d>& G,
                            const std::vector<Eigen::Isometry3d>& A,
                            const std::vector<std::pair<size_t, size_t>>& index_pairs) {
  std::vector<double> trans, rot;
  for (const auto& [i, j] : index_pairs) {
    const Eigen::Isometry3d E = (G[i].inverse() * G[j]).inverse() * (A[i].inverse() * A[j]);
    trans.push_back(E.translation().norm());
    rot.push_back(rotationAngleDeg(E.linear()));
  }
  return {computeStats(trans), computeStats(rot)};
}

/// Sum of the time spans between consecutive estimate poses, gaps longer than 1 s (lost track,
/// reset) excluded, over the ground-truth duration.
double coverageOf(const Trajectory& gt, const std::vector<double>& times) {
  if (gt.size() < 2 || times.size() < 2) return 0.0;
  double covered = 0;
  for (size_t k = 1; k < times.size(); ++k) {
    const double gap = times[k] - times[k - 1];
    if (gap <= 1.0) covered += gap;
  }
  return std::min(1.0, covered / (gt.back().t - gt.front().t));
}

}  // namespace

EvalResult evaluate(const Trajectory& gt, const Trajectory& est, const EvalOptions& options) {
  EvalResult r;
  r.pairs = options.associate_by_index ? associateByIndex(gt, est)
                                       : associateByTime(gt, est, options.max_dt);
  if (r.pairs.size() < 3)
    throw std::runtime_error("only " + std::to_string(r.pairs.size()) +
                             " pose pairs associate (need 3; check timestamps and --max-dt)");
  std::vector<Eigen::Vector3d> g, e;
  for (const auto& [gi, ei] : r.pairs) {
    g.push_back(gt[gi].p);
    e.push_back(est[ei].p);
  }
  r.alignment = align(g, e, options.align);
  const Eigen::Quaterniond align_q(r.alignment.R);
  for (const StampedPose& p : est) {
    StampedPose a = p;
    a.p = r.alignment.apply(p.p);
    a.q = align_q * p.q;
    r.aligned_estimate.push_back(a);
  }

  std::vector<Eigen::Isometry3d> G, A;
  std::vector<double> rot_sq;
  for (const auto& [gi, ei] : r.pairs) {
    const StampedPose& a = r.aligned_estimate[ei];
    r.times.push_back(a.t);
    r.errors.push_back((a.p - gt[gi].p).norm());
    G.push_back(toIsometry(gt[gi]));
    A.push_back(toIsometry(a));
    rot_sq.push_back(std::pow(a.q.angularDistance(gt[gi].q) * kRadToDeg, 2));
  }
  r.ate = computeStats(r.errors);
  double sum = 0;
  for (double x : rot_sq) sum += x;
  r.ate_rotation_rmse_deg = std::sqrt(sum / rot_sq.size());

  // RPE pairs: by frame delta, and by the first pose at least `rpe_distance` metres further along
  // the ground-truth path.
  std::vector<std::pair<size_t, size_t>> by_frames, by_distance;
  const int delta = std::max(1, options.rpe_frames);
  for (size_t i = 0; i + delta < G.size(); ++i) by_frames.emplace_back(i, i + delta);
  std::vector<double> path(G.size(), 0.0);
  for (size_t k = 1; k < G.size(); ++k)
    path[k] = path[k - 1] + (G[k].translation() - G[k - 1].translation()).norm();
  size_t j = 0;
  for (size_t i = 0; i < G.size(); ++i) {
    j = std::max(j, i);
    while (j < G.size() && path[j] - path[i] < options.rpe_distance) ++j;
    if (j == G.size()) break;
    by_distance.emplace_back(i, j);
  }
  r.rpe_frames = relativeError(G, A, by_frames);
  r.rpe_distance = relativeError(G, A, by_distance);
  r.coverage = coverageOf(gt, r.times);
  return r;
}

}  // namespace rpvio::eval
