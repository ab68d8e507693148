#pragma once
// Alignment of an estimated trajectory to the ground truth before computing the ATE:
// x_gt ≈ s R x_est + t.
#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace rpvio::eval {

enum class AlignMode {
  None,
  SE3,     // Umeyama, rotation + translation
  Sim3,    // Umeyama with scale (monocular without IMU)
  PosYaw,  // yaw about world z + translation: the 4 unobservable DoF of VIO
};

AlignMode parseAlignMode(const std::string& text);  // "se3" | "sim3" | "posyaw" | "none"
std::string toString(AlignMode mode);

struct Similarity {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  double s = 1.0;
  Eigen::Vector3d apply(const Eigen::Vector3d& x) const { return s * R * x + t; }
};

/// Least-squares alignment of the points `est` onto `gt` (same length, column i ↔ column i).
Similarity align(const std::vector<Eigen::Vector3d>& gt, const std::vector<Eigen::Vector3d>& est,
                 AlignMode mode);

}  // namespace rpvio::eval
