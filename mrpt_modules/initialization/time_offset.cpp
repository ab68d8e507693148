#include "mrpt_modules/initialization/time_offset.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "mrpt_modules/imu/so3.h"

namespace rpvio {
namespace {

/// Angular rate at time t, linear between samples (t within the samples).
Eigen::Vector3d rateAt(const std::vector<ImuSample>& s, double t) {
  const auto next =
      std::upper_bound(s.begin(), s.end(), t, [](double x, const ImuSample& a) { return x < a.t; });
  if (next == s.begin()) return s.front().gyro;
  if (next == s.end()) return s.back().gyro;
  const ImuSample& a = *(next - 1);
  const double w = (t - a.t) / (next->t - a.t);
  return (1 - w) * a.gyro + w * next->gyro;
}

/// Gyroscope rotation from time a to time b (a ≤ b), midpoint rule between sample times.
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

}  // namespace

std::optional<TimeOffsetEstimate> estimateTimeOffset(const std::vector<double>& frame_t,
                                                     const std::vector<Eigen::Matrix3d>& R_w_b,
                                                     const std::vector<ImuSample>& samples,
                                                     const Eigen::Vector3d& gyro_bias,
                                                     double max_offset, std::string* why_not) {
  auto fail = [&](const std::string& why) {
    if (why_not) *why_not = why;
    return std::nullopt;
  };
  std::vector<size_t> used;
  for (size_t k = 0; k < frame_t.size(); ++k)
    if (!samples.empty() && frame_t[k] - max_offset >= samples.front().t &&
        frame_t[k] + max_offset <= samples.back().t)
      used.push_back(k);
  if (used.size() < 4) return fail(std::to_string(used.size()) + " frames within the IMU samples");
  const size_t ref = used.front();
  const int rows = 3 * static_cast<int>(used.size() - 1);

  // Residuals for x = (b_g, td); td kept within ±max_offset.
  auto residuals = [&](const Eigen::Vector4d& x) {
    Eigen::VectorXd r(rows);
    const double td = x(3);
    for (size_t i = 1; i < used.size(); ++i) {
      const size_t k = used[i];
      const Eigen::Matrix3d gyro =
          gyroRotation(samples, frame_t[ref] + td, frame_t[k] + td, x.head<3>());
      const Eigen::AngleAxisd error(gyro.transpose() * R_w_b[ref].transpose() * R_w_b[k]);
      r.segment<3>(3 * static_cast<int>(i - 1)) = error.angle() * error.axis();
    }
    return r;
  };
  Eigen::Vector4d x;
  x << gyro_bias, 0;
  const Eigen::Vector4d step(1e-5, 1e-5, 1e-5, 1e-4);
  Eigen::MatrixXd J(rows, 4);
  Eigen::VectorXd r = residuals(x);
  for (int iteration = 0; iteration < 10; ++iteration) {
    for (int c = 0; c < 4; ++c) {
      Eigen::Vector4d plus = x, minus = x;
      plus(c) += step(c);
      minus(c) -= step(c);
      J.col(c) = (residuals(plus) - residuals(minus)) / (2 * step(c));
    }
    const Eigen::Matrix4d H = J.transpose() * J;
    const Eigen::LDLT<Eigen::Matrix4d> ldlt(H);
    if (ldlt.info() != Eigen::Success || ldlt.vectorD().minCoeff() <= 1e-12 * H.trace())
      return fail("rotations do not constrain the offset (angular rate constant?)");
    const Eigen::Vector4d dx = -ldlt.solve(J.transpose() * r);
    x += dx;
    x(3) = std::clamp(x(3), -max_offset, max_offset);
    r = residuals(x);
    if (std::abs(dx(3)) < 1e-6 && dx.head<3>().norm() < 1e-8) break;
  }
  const double dof = std::max(1, rows - 4);
  const double variance = r.squaredNorm() / dof;
  TimeOffsetEstimate e;
  e.td = x(3);
  e.gyro_bias = x.head<3>();
  e.sigma = std::sqrt(variance * (J.transpose() * J).inverse()(3, 3));
  e.rms_deg = std::sqrt(r.squaredNorm() / static_cast<double>(used.size() - 1)) * 180 / M_PI;
  e.frames = used.size();
  return e;
}

}  // namespace rpvio
