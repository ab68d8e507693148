#include "mrpt_modules/initialization/time_offset.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "mrpt_modules/imu/gyro_rotation.h"

namespace rpvio {
namespace {

/// Gauss–Newton over x = (b_g, td) on the frames `used` (the first is the reference); td kept
/// within ±max_offset. The estimate with its residuals and Jacobian, or why it has none.
struct OffsetFit {
  Eigen::Vector4d x;
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
};
std::optional<OffsetFit> fitOffset(const std::vector<double>& frame_t,
                                   const std::vector<Eigen::Matrix3d>& R_w_b,
                                   const std::vector<ImuSample>& samples,
                                   const Eigen::Vector3d& gyro_bias, double max_offset,
                                   const std::vector<size_t>& used) {
  const size_t ref = used.front();
  const int rows = 3 * static_cast<int>(used.size() - 1);
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
  OffsetFit fit;
  fit.x << gyro_bias, 0;
  const Eigen::Vector4d step(1e-5, 1e-5, 1e-5, 1e-4);
  fit.J.resize(rows, 4);
  fit.r = residuals(fit.x);
  for (int iteration = 0; iteration < 10; ++iteration) {
    for (int c = 0; c < 4; ++c) {
      Eigen::Vector4d plus = fit.x, minus = fit.x;
      plus(c) += step(c);
      minus(c) -= step(c);
      fit.J.col(c) = (residuals(plus) - residuals(minus)) / (2 * step(c));
    }
    const Eigen::Matrix4d H = fit.J.transpose() * fit.J;
    const Eigen::LDLT<Eigen::Matrix4d> ldlt(H);
    if (ldlt.info() != Eigen::Success || ldlt.vectorD().minCoeff() <= 1e-12 * H.trace())
      return std::nullopt;
    const Eigen::Vector4d dx = -ldlt.solve(fit.J.transpose() * fit.r);
    fit.x += dx;
    fit.x(3) = std::clamp(fit.x(3), -max_offset, max_offset);
    fit.r = residuals(fit.x);
    if (std::abs(dx(3)) < 1e-6 && dx.head<3>().norm() < 1e-8) break;
  }
  return fit;
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
  const auto fit = fitOffset(frame_t, R_w_b, samples, gyro_bias, max_offset, used);
  if (!fit) return fail("rotations do not constrain the offset (angular rate constant?)");
  const Eigen::VectorXd& r = fit->r;
  const int rows = static_cast<int>(r.size());

  // The residuals are not independent: all share the reference frame's rotation error, and the
  // structure from motion's errors drift smoothly, so the residual variance times (JᵀJ)⁻¹ is too
  // small. With ρ the residuals' lag-1 autocorrelation from frame to frame, an AR(1) model counts
  // n residuals as n (1 − ρ)/(1 + ρ) independent ones (ρ taken in [0, 0.95]).
  double lag0 = 0, lag1 = 0;
  for (int i = 0; i < rows; ++i) lag0 += r(i) * r(i);
  for (int i = 3; i < rows; ++i) lag1 += r(i) * r(i - 3);
  TimeOffsetEstimate e;
  e.residual_correlation = lag0 > 0 ? std::clamp(lag1 / lag0, 0.0, 0.95) : 0.0;
  const double rho = e.residual_correlation;
  const double variance = lag0 / std::max(1, rows - 4) * (1 + rho) / (1 - rho);
  e.td = fit->x(3);
  e.gyro_bias = fit->x.head<3>();
  const double td_cofactor = (fit->J.transpose() * fit->J).inverse()(3, 3);
  e.sigma = std::sqrt(variance * td_cofactor);
  // A residual-sized error e shifts td by (J⁺e)_td, at most ‖e‖ √((JᵀJ)⁻¹)_td,td (Cauchy–Schwarz):
  // the systematic part that sigma's noise model cannot see.
  e.systematic = std::sqrt(lag0 * td_cofactor);
  e.rms_deg = std::sqrt(lag0 / static_cast<double>(used.size() - 1)) * 180 / M_PI;
  e.frames = used.size();
  return e;
}

}  // namespace rpvio
