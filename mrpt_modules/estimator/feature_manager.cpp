#include "mrpt_modules/estimator/feature_manager.h"

#include <Eigen/Dense>
#include <algorithm>

namespace rpvio {
namespace {

Eigen::Vector3d ray(const Eigen::Vector2d& u) { return Eigen::Vector3d(u.x(), u.y(), 1); }

}  // namespace

void FeatureManager::addFrame(uint64_t frame, const FeatureFrame& features) {
  for (const auto& f : features.features) {
    FeatureTrack& track = tracks_[f.id];
    track.id = f.id;
    track.plane_id = f.plane_id;
    track.observations.push_back({frame, f.normalized});
  }
}

Eigen::Vector3d FeatureManager::worldPoint(const FeatureTrack& track,
                                           const CameraPoseLookup& cameras) const {
  const TrackObservation& anchor = track.observations.front();
  return cameras(anchor.frame) * (ray(anchor.normalized) / track.inv_depth[0]);
}

void FeatureManager::removeFrame(uint64_t frame, const CameraPoseLookup& cameras) {
  for (auto it = tracks_.begin(); it != tracks_.end();) {
    FeatureTrack& track = it->second;
    auto& obs = track.observations;
    const auto found = std::find_if(obs.begin(), obs.end(),
                                    [&](const TrackObservation& o) { return o.frame == frame; });
    if (found == obs.end()) {
      ++it;
      continue;
    }
    if (found == obs.begin() && obs.size() > 1 && track.triangulated) {
      const Eigen::Vector3d X_c = cameras(obs[1].frame).inverse() * worldPoint(track, cameras);
      if (X_c.z() > 0)
        track.inv_depth[0] = 1.0 / X_c.z();
      else
        track.triangulated = false;
    }
    obs.erase(found);
    if (obs.empty())
      it = tracks_.erase(it);
    else
      ++it;
  }
}

double widestRayAngle(const FeatureTrack& track, const CameraPoseLookup& cameras) {
  const auto world_ray = [&](const TrackObservation& o) {
    return (cameras(o.frame).linear() * ray(o.normalized)).normalized();
  };
  const Eigen::Vector3d r0 = world_ray(track.observations.front());
  double widest = 0;
  for (const auto& o : track.observations)
    widest = std::max(widest, std::acos(std::clamp(r0.dot(world_ray(o)), -1.0, 1.0)));
  return widest;
}

std::optional<double> linearAnchorDepth(const FeatureTrack& track,
                                        const CameraPoseLookup& cameras) {
  // Linear triangulation in the anchor camera: each view gives u × (R X + t) = 0 (two rows).
  const Eigen::Isometry3d anchor = cameras(track.observations.front().frame);
  Eigen::MatrixXd A(2 * track.observations.size(), 4);
  for (size_t k = 0; k < track.observations.size(); ++k) {
    const auto& o = track.observations[k];
    const Eigen::Isometry3d c_from_anchor = cameras(o.frame).inverse() * anchor;
    Eigen::Matrix<double, 3, 4> P;
    P << c_from_anchor.linear(), c_from_anchor.translation();
    A.row(2 * k) = o.normalized.x() * P.row(2) - P.row(0);
    A.row(2 * k + 1) = o.normalized.y() * P.row(2) - P.row(1);
  }
  const Eigen::Vector4d X =
      Eigen::JacobiSVD<Eigen::MatrixXd>(A, Eigen::ComputeFullV).matrixV().col(3);
  if (std::abs(X(3)) < 1e-12) return std::nullopt;
  return X(2) / X(3);
}

void FeatureManager::triangulate(const CameraPoseLookup& cameras, double min_angle_rad,
                                 double min_depth, double max_depth) {
  for (auto& [id, track] : tracks_) {
    if (track.triangulated || track.observations.size() < 2) continue;
    if (widestRayAngle(track, cameras) < min_angle_rad) continue;
    const std::optional<double> depth = linearAnchorDepth(track, cameras);
    if (!depth || *depth < min_depth || *depth > max_depth) continue;
    track.inv_depth[0] = 1.0 / *depth;
    track.triangulated = true;
  }
}

}  // namespace rpvio
