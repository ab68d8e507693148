#pragma once
// SO(3) helpers for the IMU code: hat, exponential map and right Jacobian.
#include <Eigen/Geometry>

namespace rpvio {

inline Eigen::Matrix3d hat(const Eigen::Vector3d& w) {
  Eigen::Matrix3d m;
  m << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return m;
}

inline Eigen::Quaterniond expQuaternion(const Eigen::Vector3d& w) {
  const double angle = w.norm();
  if (angle < 1e-12)
    return Eigen::Quaterniond(1, 0.5 * w.x(), 0.5 * w.y(), 0.5 * w.z()).normalized();
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, w / angle));
}

/// Right Jacobian of SO(3): Exp(w + δ) ≈ Exp(w) Exp(J_r(w) δ) (Forster et al. 2017, Eq. 8).
inline Eigen::Matrix3d rightJacobian(const Eigen::Vector3d& w) {
  const double a = w.norm();
  const Eigen::Matrix3d W = hat(w);
  if (a < 1e-6) return Eigen::Matrix3d::Identity() - 0.5 * W + W * W / 6.0;
  return Eigen::Matrix3d::Identity() - (1 - std::cos(a)) / (a * a) * W +
         (a - std::sin(a)) / (a * a * a) * W * W;
}

}  // namespace rpvio
