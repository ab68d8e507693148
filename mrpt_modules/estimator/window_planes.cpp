#include "mrpt_modules/estimator/window_planes.h"

#include <ceres/sphere_manifold.h>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <optional>
#include <utility>

#include "mrpt_modules/factors/marginal_covariance.h"

namespace rpvio {
namespace {

// Planarity of the triangulated points of a new plane: their rms distance to the fitted plane, as
// a fraction of their distance to the newest camera (triangulation error grows with depth).
constexpr double kMaxPlaneRmsPerDepth = 0.04;
// Until a covariance has been computed, a plane is handed to the map with this standard deviation
// of (n, d) for one supporting point.
constexpr double kPlaneSigmaPerPoint = 0.05;
// Plane parameters handed to the planes map, which fuses visits by information. Their covariance
// is the window's, relative to its oldest pose; between visits the odometry drifts (the simulator's
// trajectory errors: 0.1 deg, 3 cm), which no visit is trusted beyond.
constexpr double kVisitDriftNormalDeg = 0.2, kVisitDriftDistance = 0.03;

/// Covariance of (n, d) of a plane not yet solved in the window, fitted to `points` points.
Eigen::Matrix4d unsolvedCovariance(size_t points) {
  return Eigen::Matrix4d::Identity() * kPlaneSigmaPerPoint * kPlaneSigmaPerPoint /
         static_cast<double>(points);
}

/// The plane through `points` (least squares; d ≥ 0), when they are planar within
/// kMaxPlaneRmsPerDepth of their distance to the newest camera.
std::optional<std::pair<Eigen::Vector3d, double>> fitPlane(
    const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& newest_camera) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : points) mean += p / points.size();
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& p : points) cov += (p - mean) * (p - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  const double depth = (mean - newest_camera).norm();
  if (std::sqrt(eig.eigenvalues()(0) / points.size()) > kMaxPlaneRmsPerDepth * depth)
    return std::nullopt;
  Eigen::Vector3d n = eig.eigenvectors().col(0);
  if (n.dot(mean) < 0) n = -n;  // convention: d ≥ 0
  return std::pair{n, n.dot(mean)};
}

/// World points of the label's triangulated tracks seen at least 3 times; the ground's twice: its
/// tracks live a few images (GroundTracks' max_length), and few reach a third keyframe at a car's
/// speed (kitti07 started at frame 40: 1–12 such points per window for 7 s, no ground plane).
std::vector<Eigen::Vector3d> pointsOfPlane(int plane, const FeatureManager& features,
                                           const CameraPoseLookup& cameras) {
  const size_t min_observations = plane == kGroundLabel ? 2 : 3;
  std::vector<Eigen::Vector3d> points;
  for (const auto& [id, track] : features.tracks())
    if (track.plane_id == plane && track.triangulated &&
        track.observations.size() >= min_observations)
      points.push_back(features.worldPoint(track, cameras));
  return points;
}

}  // namespace

PlaneEstimate WindowPlanes::newEstimate(const double* normal, double distance) {
  PlaneEstimate e;
  for (int i = 0; i < 3; ++i) e.normal[i] = normal[i];
  e.distance[0] = distance;
  e.visit = ++visits_;
  return e;
}

void WindowPlanes::choose(const FeatureManager& features, const std::set<int>* eligible) {
  std::map<int, size_t> count;  // tracks per plane label in the window
  for (const auto& [id, track] : features.tracks())
    if (track.plane_id > 0 && (!eligible || eligible->count(track.plane_id)))
      ++count[track.plane_id];
  if (which_ != HomographyPlanes::kLargest) {
    used_.clear();
    if (which_ == HomographyPlanes::kAll)
      for (const auto& [plane, n] : count) used_.insert(plane);
    return;
  }
  // Largest plane, with hysteresis: the current one stays while it keeps 70% of the best count.
  // The ground's tracks (ground_tracks.h) have their factors besides: the homography of their
  // plane is all they measure.
  const bool ground = count.erase(kGroundLabel) > 0;
  int best = -1;
  size_t best_count = 0;
  for (const auto& [plane, n] : count)
    if (n > best_count) best = plane, best_count = n;
  const int current = largest_;
  if (!(current > 0 && count.count(current) && count[current] >= 0.7 * best_count)) largest_ = best;
  used_.clear();
  if (largest_ > 0) used_.insert(largest_);
  if (ground) used_.insert(kGroundLabel);
}

void WindowPlanes::initialize(const FeatureManager& features, const CameraPoseLookup& cameras,
                              const Eigen::Vector3d& newest_camera, const PlanesMap& map) {
  for (int plane : used_) {
    if (planes_.count(plane)) continue;
    if (const Plane* known = map.planeOfMask(plane)) {
      planes_[plane] = newEstimate(known->normal.data(), known->distance);
      continue;
    }
    const std::vector<Eigen::Vector3d> points = pointsOfPlane(plane, features, cameras);
    if (points.size() < kMinPlanePoints) continue;
    if (const auto fit = fitPlane(points, newest_camera))
      planes_[plane] = newEstimate(fit->first.data(), fit->second);
  }
}

std::vector<PlaneObservation> WindowPlanes::fittedObservations(const FeatureManager& features,
                                                               const CameraPoseLookup& cameras,
                                                               double t,
                                                               const Eigen::Vector3d& newest_camera,
                                                               const std::set<int>* eligible) {
  std::set<int> labels;
  for (const auto& [id, track] : features.tracks())
    if (track.plane_id > 0 && !planes_.count(track.plane_id) &&
        (!eligible || eligible->count(track.plane_id)))
      labels.insert(track.plane_id);
  std::vector<PlaneObservation> out;
  std::map<int, uint64_t> visits;  // the labels fitted now, in the visit they were in or a new one
  for (int label : labels) {
    PlaneObservation o;
    o.points = pointsOfPlane(label, features, cameras);
    if (o.points.size() < kMinPlanePoints) continue;
    const auto fit = fitPlane(o.points, newest_camera);
    if (!fit) continue;
    o.mask_id = label;
    o.normal = fit->first;
    o.distance = fit->second;
    o.covariance = unsolvedCovariance(o.points.size());
    o.time = t;
    const auto stay = fitted_visits_.find(label);
    o.visit = visits[label] = stay != fitted_visits_.end() ? stay->second : ++visits_;
    out.push_back(std::move(o));
  }
  fitted_visits_ = std::move(visits);
  return out;
}

std::set<int> WindowPlanes::constrained(const FeatureManager& features) const {
  std::map<int, size_t> tracks;
  for (const auto& [id, track] : features.tracks())
    if (inUse(track)) ++tracks[track.plane_id];
  std::set<int> labels;
  for (const auto& [plane, n] : tracks)
    if (n >= kMinPlanePoints) labels.insert(plane);
  return labels;
}

PlaneEstimate* WindowPlanes::homographyPlane(const FeatureTrack& track,
                                             const std::set<int>& constrained) {
  const auto plane = planes_.find(track.plane_id);
  return used_.count(track.plane_id) && constrained.count(track.plane_id) && plane != planes_.end()
             ? &plane->second
             : nullptr;
}

void WindowPlanes::start(const std::map<int, WorldPlane>& planes) {
  planes_.clear();
  for (const auto& [mask, plane] : planes) planes_[mask] = newEstimate(plane.n.data(), plane.d);
}

std::vector<PlaneObservation> WindowPlanes::observations(const FeatureManager& features,
                                                         const CameraPoseLookup& cameras,
                                                         double t) const {
  std::vector<PlaneObservation> out;
  for (const auto& [mask, estimate] : planes_) {
    PlaneObservation o;
    o.mask_id = mask;
    o.normal = Eigen::Vector3d(estimate.normal).normalized();
    o.distance = estimate.distance[0];
    for (const auto& [id, track] : features.tracks())
      if (track.plane_id == mask && track.triangulated)
        o.points.push_back(features.worldPoint(track, cameras));
    if (o.points.size() < kMinPlanePoints) continue;
    o.covariance = estimate.covariance.value_or(unsolvedCovariance(o.points.size()));
    o.time = t;
    o.visit = estimate.visit;
    out.push_back(std::move(o));
  }
  return out;
}

bool WindowPlanes::updateCovariances(ceres::Problem& problem, const std::set<int>& planes) {
  std::vector<double*> blocks;
  for (int mask : planes) {
    blocks.push_back(planes_.at(mask).normal);
    blocks.push_back(planes_.at(mask).distance);
  }
  if (blocks.empty()) return false;
  const auto covariance = marginalCovariance(problem, blocks);
  if (!covariance) return false;  // not evaluable: the planes keep their last covariance
  const double drift_normal = kVisitDriftNormalDeg * M_PI / 180;
  int offset = 0;
  for (int mask : planes) {
    PlaneEstimate& e = planes_.at(mask);
    // Tangent (2 normal numbers on the sphere, d) to ambient (n, d).
    Eigen::Matrix<double, 3, 2, Eigen::RowMajor> plus;
    ceres::SphereManifold<3>().PlusJacobian(e.normal, plus.data());
    Eigen::Matrix<double, 4, 3> E = Eigen::Matrix<double, 4, 3>::Zero();
    E.topLeftCorner<3, 2>() = plus;
    E(3, 2) = 1;
    Eigen::Matrix4d C = E * covariance->block<3, 3>(offset, offset) * E.transpose();
    const Eigen::Vector3d n = Eigen::Vector3d(e.normal).normalized();
    C.topLeftCorner<3, 3>() +=
        drift_normal * drift_normal * (Eigen::Matrix3d::Identity() - n * n.transpose());
    C(3, 3) += kVisitDriftDistance * kVisitDriftDistance;
    e.covariance = C;
    offset += 3;
  }
  return true;
}

}  // namespace rpvio
