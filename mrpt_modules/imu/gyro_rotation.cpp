#include "mrpt_modules/imu/gyro_rotation.h"

#include <algorithm>

#include "mrpt_modules/imu/so3.h"

namespace rpvio {
namespace {

/// Angular rate at time t, linear between samples, held outside them.
Eigen::Vector3d rateAt(const std::vector<ImuSample>& s, double t) {
  const auto next =
      std::upper_bound(s.begin(), s.end(), t, [](double x, const ImuSample& a) { return x < a.t; });
  if (next == s.begin()) return s.front().gyro;
  if (next == s.end()) return s.back().gyro;
  const ImuSample& a = *(next - 1);
  const double w = (t - a.t) / (next->t - a.t);
  return (1 - w) * a.gyro + w * next->gyro;
}

}  // namespace

Eigen::Matrix3d gyroRotation(const std::vector<ImuSample>& s, double a, double b,
                             const Eigen::Vector3d& bias) {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  auto it =
      std::upper_bound(s.begin(), s.end(), a, [](double x, const ImuSample& q) { return x < q.t; });
  double t = a;
  while (t < b) {
    const double end = (it != s.end() && it->t < b) ? it->t : b;
    const Eigen::Vector3d w = rateAt(s, 0.5 * (t + end)) - bias;
    R = R * expQuaternion(w * (end - t)).toRotationMatrix();
    t = end;
    if (it != s.end()) ++it;
  }
  return R;
}

Eigen::Matrix3d cameraRotationBetween(const std::vector<ImuSample>& samples, double a, double b,
                                      const Eigen::Matrix3d& R_BC) {
  return R_BC.transpose() * gyroRotation(samples, a, b, Eigen::Vector3d::Zero()).transpose() * R_BC;
}

}  // namespace rpvio
