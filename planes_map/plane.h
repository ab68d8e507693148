#pragma once
// A persistent plane of the map: world plane n·X = d (unit n), its uncertainty, the points that
// support it (bounded, voxel-decimated) and its extent (convex hull of the support in the plane).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <set>
#include <vector>

#include "common/oscillating_translation.h"

namespace rpvio {

/// Labels of discovered planes (rpvio-auto) start here, above the 8-bit mask labels.
constexpr int kFirstDiscoveredLabel = 256;
/// The label of the ground tracked by direct alignment (mrpt_modules/frontend/ground_tracks.h).
constexpr int kGroundLabel = 1 << 20;

struct Plane {
  int id = 0;                                                // stable map id
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();         // world frame, unit
  double distance = 0;                                       // n·X = d
  Eigen::Matrix4d covariance = Eigen::Matrix4d::Identity();  // of (n, d), ambient
  std::vector<Eigen::Vector3d> support;                      // world points, decimated
  std::vector<Eigen::Vector3d> polygon;  // convex hull of the support, on the plane
  size_t observations = 0;
  double first_seen = 0, last_seen = 0;  // s
  std::set<int> mask_ids;                // labels it was seen as
  // Ground truth of a moving planar object (simulator): normal, distance and polygon are at t = 0;
  // at time t every point X(0) is at X(0) + motion.offset(t) − motion.offset(0).
  bool moving = false;
  OscillatingTranslation motion;

  /// Found by the plane discovery (rpvio-auto).
  bool discovered() const {
    return !mask_ids.empty() && *mask_ids.begin() >= kFirstDiscoveredLabel;
  }
  /// Distance of a point to the plane (signed).
  double signedDistance(const Eigen::Vector3d& x) const { return normal.dot(x) - distance; }
  /// An orthonormal in-plane basis (u, v) with u × v = n, and the point of the plane nearest 0.
  void planeFrame(Eigen::Vector3d& origin, Eigen::Vector3d& u, Eigen::Vector3d& v) const;
  /// Recomputes `polygon` from `support` (2D convex hull in the plane frame).
  void updatePolygon();
  /// Support for a plane read from a file (which keeps its outline only): the polygon's vertices
  /// and a grid of `spacing` inside it.
  void supportFromPolygon(double spacing);
  /// Voxel-grid decimation of `support` to one point per cell, at most `max_points` kept.
  void decimateSupport(double voxel_size, size_t max_points);
  /// The plane in another frame, X' = T X: n' = R n, d' = d + n'ᵀt, the covariance carried by the
  /// Jacobian [[R, 0], [tᵀR, 1]] of (n', d') in (n, d); support, polygon and motion moved alike.
  Plane transformed(const Eigen::Isometry3d& T) const;
};

}  // namespace rpvio
