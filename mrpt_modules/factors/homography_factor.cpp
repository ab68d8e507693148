#include "mrpt_modules/factors/homography_factor.h"

#include <Eigen/Geometry>

#include "mrpt_modules/factors/parameter_blocks.h"
#include "mrpt_modules/factors/pose_manifold.h"
#include "mrpt_modules/imu/so3.h"

namespace rpvio {

double visionSqrtInfo(double focal_px, double sigma_px) { return focal_px / sigma_px; }

bool HomographyResidual::Evaluate(double const* const* x, double* residuals,
                                  double** jacobians) const {
  const Eigen::Vector3d Pi = posePosition(x[0]), tic = posePosition(x[2]);
  const Eigen::Matrix3d Ri = poseRotation(x[0]).normalized().toRotationMatrix();
  const Eigen::Matrix3d Ric = poseRotation(x[2]).normalized().toRotationMatrix();
  const Eigen::Map<const Eigen::Vector3d> n_w(x[3]);
  const double d_w = x[4][0];
  // ρ = a / b: a = n_ci·ū_i = n_w·(R_wci ū_i), b = d_ci = d_w − n_w·p_wci.
  const Eigen::Vector3d u(u_i_.x(), u_i_.y(), 1);
  const Eigen::Vector3d ray_w = Ri * Ric * u, p_wci = Ri * tic + Pi;
  const double a = n_w.dot(ray_w), b = d_w - n_w.dot(p_wci);
  if (a == 0 || b == 0) return false;  // ray parallel to the plane, or camera on it
  const double rho = a / b;

  const double* reprojection_blocks[4] = {x[0], x[1], x[2], &rho};
  Eigen::Vector2d d_rho;  // ∂r/∂ρ
  double* reprojection_jacobians[4] = {nullptr, nullptr, nullptr, d_rho.data()};
  if (jacobians)
    for (int k = 0; k < 3; ++k) reprojection_jacobians[k] = jacobians[k];
  if (!reprojection_.Evaluate(reprojection_blocks, residuals,
                              jacobians ? reprojection_jacobians : nullptr))
    return false;
  if (!jacobians) return true;

  const double a_b2 = a / (b * b);
  if (jacobians[0]) {  // R_i Exp(δθ), P_i + δp: ∂a = ūᵀR_icᵀ[R_iᵀn]× δθ, ∂b = n_wᵀR_i[t_ic]× δθ −
                       // n_wᵀ δp
    Eigen::Matrix<double, 1, 6> J;
    J.leftCols<3>() = a_b2 * n_w.transpose();
    J.rightCols<3>() = (Ric * u).transpose() * hat(Ri.transpose() * n_w) / b -
                       a_b2 * n_w.transpose() * Ri * hat(tic);
    Eigen::Map<Eigen::Matrix<double, 2, 7, Eigen::RowMajor>> J_pose_i(jacobians[0]);
    J_pose_i += tangentToAmbient<2>(d_rho * J, x[0]);
  }
  if (jacobians[2]) {  // R_ic Exp(δφ), t_ic + δt: ∂a = ūᵀ[n_ci]× δφ, ∂b = −n_wᵀR_i δt
    const Eigen::Vector3d n_ci = Ric.transpose() * Ri.transpose() * n_w;
    Eigen::Matrix<double, 1, 6> J;
    J.leftCols<3>() = a_b2 * n_w.transpose() * Ri;
    J.rightCols<3>() = u.transpose() * hat(n_ci) / b;
    Eigen::Map<Eigen::Matrix<double, 2, 7, Eigen::RowMajor>> J_mount(jacobians[2]);
    J_mount += tangentToAmbient<2>(d_rho * J, x[2]);
  }
  if (jacobians[3]) {  // ∂a/∂n = ray_wᵀ, ∂b/∂n = −p_wciᵀ
    Eigen::Map<Eigen::Matrix<double, 2, 3, Eigen::RowMajor>> J_normal(jacobians[3]);
    J_normal = d_rho * (ray_w.transpose() / b + a_b2 * p_wci.transpose());
  }
  if (jacobians[4]) {
    Eigen::Map<Eigen::Vector2d> J_distance(jacobians[4]);
    J_distance = -a_b2 * d_rho;
  }
  return true;
}

}  // namespace rpvio
