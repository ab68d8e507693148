#include "planes_map/planes_map.h"

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <sstream>

#include "common/input_error.h"

namespace rpvio {
namespace {

/// Smallest distance between two point sets (brute force on the decimated supports).
double gapBetween(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& p : a)
    for (const auto& q : b) best = std::min(best, (p - q).squaredNorm());
  return std::sqrt(best);
}

Eigen::Vector3d centroid(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const auto& p : points) sum += p;
  return sum / static_cast<double>(points.size());
}

}  // namespace

bool PlanesMap::compatible(const Plane& plane, const Eigen::Vector3d& n, double d,
                           const std::vector<Eigen::Vector3d>& points, bool same_label) const {
  const double max_angle =
      same_label ? options_.max_label_normal_angle_deg : options_.max_normal_angle_deg;
  const double max_distance = same_label ? options_.max_label_distance_m : options_.max_distance_m;
  const double sign = plane.normal.dot(n) < 0 ? -1 : 1;  // (−n, −d) is the same plane
  const double angle = std::acos(std::clamp(sign * plane.normal.dot(n), -1.0, 1.0)) * 180 / M_PI;
  // The offset where the observation is: its points' centroid against the plane (d at the world
  // origin moves by metres with a few degrees of normal when the plane is 20 m away).
  const double offset = points.empty() ? std::abs(plane.distance - sign * d)
                                       : std::abs(plane.signedDistance(centroid(points)));
  if (angle > max_angle || offset > max_distance) return false;
  if (same_label || points.empty() || plane.support.empty()) return true;
  return gapBetween(plane.support, points) <= options_.max_gap_m;
}

namespace {

/// The observation as (−n, −d) if its normal points away from `reference`: the same plane n·X = d
/// (the homography residual cannot tell the two apart, so a window's estimate may come back
/// flipped after a bad stretch). The covariance of (n, d) is unchanged by the sign.
PlaneObservation orientedLike(const Eigen::Vector3d& reference, PlaneObservation o) {
  if (reference.dot(o.normal) < 0) {
    o.normal = -o.normal;
    o.distance = -o.distance;
  }
  return o;
}

/// The tangent of (n, d) at unit n as columns of ambient 4-vectors: tilts along the plane's
/// in-plane basis (u, v), then d.
Eigen::Matrix<double, 4, 3> tangentBasis(const Eigen::Vector3d& n) {
  Plane frame;
  frame.normal = n;
  Eigen::Vector3d origin, u, v;
  frame.planeFrame(origin, u, v);
  Eigen::Matrix<double, 4, 3> E = Eigen::Matrix<double, 4, 3>::Zero();
  E.block<3, 1>(0, 0) = u;
  E.block<3, 1>(0, 1) = v;
  E(3, 2) = 1;
  return E;
}

/// Information-weighted fusion of two (n, d) estimates on the unit sphere × line: Gauss–Newton
/// in the fused normal's tangent. Each estimate's ambient covariance counts in its own tangent
/// (Eᵀ C E), so a covariance with nothing along n itself (the unit constraint) is welcome; the
/// fused covariance is ambient the same way, E Σ Eᵀ.
void fuseEstimates(Eigen::Vector3d& n, double& d, Eigen::Matrix4d& covariance,
                   const Eigen::Vector3d& n_b, double d_b, const Eigen::Matrix4d& covariance_b) {
  struct Estimate {
    double d;
    Eigen::Matrix<double, 4, 3> E;  // its tangent, where its covariance counts
    Eigen::Matrix3d information;
  };
  const auto estimate = [](const Eigen::Vector3d& n, double d, const Eigen::Matrix4d& C) {
    const Eigen::Matrix<double, 4, 3> E = tangentBasis(n);
    return Estimate{d, E, (E.transpose() * C * E).inverse()};
  };
  const Estimate estimates[2] = {estimate(n, d, covariance), estimate(n_b, d_b, covariance_b)};
  Eigen::Matrix<double, 4, 3> E = estimates[0].E;
  Eigen::Matrix3d H;
  for (int iteration = 0; iteration < 5; ++iteration) {
    H.setZero();
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    for (const Estimate& e : estimates) {
      // Residual: the fused normal's tilt in e's tangent, and the offset difference.
      const Eigen::Vector3d r(e.E.col(0).head<3>().dot(n), e.E.col(1).head<3>().dot(n), d - e.d);
      const Eigen::Matrix3d J = e.E.transpose() * E;
      H += J.transpose() * e.information * J;
      g += J.transpose() * e.information * r;
    }
    const Eigen::Vector3d step = -H.ldlt().solve(g);
    n = (n + E.topRows<3>() * step).normalized();
    d += step(2);
    E = tangentBasis(n);
  }
  covariance = E * H.inverse() * E.transpose();
}

}  // namespace

void PlanesMap::fuse(Plane& plane, const PlaneObservation& obs) const {
  fuseEstimates(plane.normal, plane.distance, plane.covariance, obs.normal, obs.distance,
                obs.covariance);
  record(plane, obs);
}

void PlanesMap::record(Plane& plane, const PlaneObservation& obs) const {
  plane.support.insert(plane.support.end(), obs.points.begin(), obs.points.end());
  plane.decimateSupport(options_.voxel_size_m, options_.max_support_points);
  plane.updatePolygon();
  plane.observations += 1;
  plane.last_seen = std::max(plane.last_seen, obs.time);
  plane.first_seen = std::min(plane.first_seen, obs.time);
  plane.mask_ids.insert(obs.mask_id);
}

int PlanesMap::addPlane(const Plane& plane, bool associate) {
  for (Plane& p : planes_) {
    if (!associate || !compatible(p, plane.normal, plane.distance, plane.support)) continue;
    PlaneObservation observation;
    observation.mask_id = plane.mask_ids.empty() ? 0 : *plane.mask_ids.begin();
    observation.normal = plane.normal;
    observation.distance = plane.distance;
    observation.covariance = plane.covariance;
    observation.points = plane.support;
    observation.time = plane.first_seen;
    fuse(p, orientedLike(p.normal, observation));
    p.observations += plane.observations - 1;  // fuse() counted one
    p.mask_ids.insert(plane.mask_ids.begin(), plane.mask_ids.end());
    p.last_seen = std::max(p.last_seen, plane.last_seen);
    return p.id;
  }
  Plane added = plane;
  added.id = next_id_++;
  planes_.push_back(added);
  return added.id;
}

int PlanesMap::update(const PlaneObservation& observation) {
  Plane* target = nullptr;
  const auto linked = mask_to_plane_.find(observation.mask_id);
  if (linked != mask_to_plane_.end()) {
    for (auto& p : planes_)
      if (p.id == linked->second &&
          compatible(p, observation.normal, observation.distance, observation.points, true))
        target = &p;
  }
  if (!target) {
    for (auto& p : planes_)
      if (compatible(p, observation.normal, observation.distance, observation.points)) {
        target = &p;
        break;
      }
  }
  const PlaneObservation obs = target ? orientedLike(target->normal, observation) : observation;
  if (!target) {
    Plane p;
    p.id = next_id_++;
    p.normal = obs.normal.normalized();
    p.distance = obs.distance;
    p.covariance = obs.covariance;
    p.first_seen = p.last_seen = obs.time;
    record(p, obs);
    planes_.push_back(p);
    mask_to_plane_[obs.mask_id] = p.id;
    if (obs.visit != 0) visit_start_[p.id] = {obs.visit, false};
    return p.id;
  }
  if (obs.visit == 0) {
    fuse(*target, obs);
  } else {
    // Same visit: the observation replaces the visit's previous one, fused with what the map
    // knew before the visit.
    VisitStart& start = visit_start_[target->id];
    if (start.visit != obs.visit)
      start = {obs.visit, true, target->normal, target->distance, target->covariance};
    target->normal = obs.normal.normalized();
    target->distance = obs.distance;
    target->covariance = obs.covariance;
    if (start.known)
      fuseEstimates(target->normal, target->distance, target->covariance, start.normal,
                    start.distance, start.covariance);
    record(*target, obs);
  }
  mask_to_plane_[obs.mask_id] = target->id;
  return target->id;
}

size_t PlanesMap::mergeDuplicates() {
  size_t merged = 0;
  for (size_t i = 0; i < planes_.size(); ++i)
    for (size_t j = i + 1; j < planes_.size();) {
      Plane& keep = planes_[i];
      const Plane& other = planes_[j];
      if (!compatible(keep, other.normal, other.distance, other.support)) {
        ++j;
        continue;
      }
      const PlaneObservation as_observation =
          orientedLike(keep.normal, {*other.mask_ids.begin(), other.normal, other.distance,
                                     other.covariance, other.support, other.first_seen});
      fuse(keep, as_observation);
      keep.observations += other.observations - 1;
      keep.last_seen = std::max(keep.last_seen, other.last_seen);
      keep.mask_ids.insert(other.mask_ids.begin(), other.mask_ids.end());
      for (auto& [mask, id] : mask_to_plane_)
        if (id == other.id) id = keep.id;
      visit_start_.erase(other.id);
      planes_.erase(planes_.begin() + static_cast<long>(j));
      ++merged;
    }
  return merged;
}

std::vector<Plane> PlanesMap::confirmedPlanes() const {
  std::vector<Plane> confirmed;
  for (const auto& p : planes_)
    if (isConfirmed(p)) confirmed.push_back(p);
  return confirmed;
}

void PlanesMap::setParameters(int id, const Eigen::Vector3d& normal, double distance) {
  for (auto& p : planes_)
    if (p.id == id) {
      p.normal = normal;
      p.distance = distance;
      p.updatePolygon();
    }
}

const Plane* PlanesMap::plane(int id) const {
  for (const auto& p : planes_)
    if (p.id == id) return &p;
  return nullptr;
}

const Plane* PlanesMap::planeOfMask(int mask_id) const {
  const auto it = mask_to_plane_.find(mask_id);
  const Plane* p = it == mask_to_plane_.end() ? nullptr : plane(it->second);
  return p && isConfirmed(*p) ? p : nullptr;
}

}  // namespace rpvio
