#include "mrpt_modules/factors/homography_factor.h"

#include <Eigen/Geometry>

#include "mrpt_modules/factors/parameter_blocks.h"
#include "mrpt_modules/factors/pose_manifold.h"
#include "mrpt_modules/imu/so3.h"

namespace rpvio {

double visionSqrtInfo(double focal_px, double sigma_px) { return focal_px / sigma_px; }

bool homographyInTangent(const TwoViewPoses& g, const Eigen::Vector3d& n_w, double d_w,
                         const Eigen::Vector2d& u_i, const Eigen::Vector2d& u_j, double sqrt_info,
                         Eigen::Vector2d& residual, TangentJacobian* J_pose_i,
                         TangentJacobian* J_pose_j, TangentJacobian* J_mount,
                         Eigen::Matrix<double, 2, 3>* J_normal, Eigen::Vector2d* J_distance) {
  // ρ = a / b: a = n_ci·ū_i = n_w·(R_wci ū_i), b = d_ci = d_w − n_w·p_wci.
  const Eigen::Vector3d u(u_i.x(), u_i.y(), 1);
  const Eigen::Vector3d ray_w = g.Ri * g.Ric * u, p_wci = g.Ri * g.tic + g.Pi;
  const double a = n_w.dot(ray_w), b = d_w - n_w.dot(p_wci);
  if (a == 0 || b == 0) return false;  // ray parallel to the plane, or camera on it
  const double rho = a / b;
  const bool any = J_pose_i || J_pose_j || J_mount || J_normal || J_distance;
  Eigen::Vector2d d_rho;  // ∂r/∂ρ
  reprojectionInTangent(g, u_i, u_j, sqrt_info, rho, residual, J_pose_i, J_pose_j, J_mount,
                        any ? &d_rho : nullptr);
  if (!any) return true;

  const double a_b2 = a / (b * b);
  if (J_pose_i) {  // R_i Exp(δθ), P_i + δp: ∂a = ūᵀR_icᵀ[R_iᵀn]× δθ, ∂b = n_wᵀR_i[t_ic]× δθ −
                   // n_wᵀ δp
    Eigen::Matrix<double, 1, 6> J;
    J.leftCols<3>() = a_b2 * n_w.transpose();
    J.rightCols<3>() = (g.Ric * u).transpose() * hat(g.Ri.transpose() * n_w) / b -
                       a_b2 * n_w.transpose() * g.Ri * hat(g.tic);
    *J_pose_i += d_rho * J;
  }
  if (J_mount) {  // R_ic Exp(δφ), t_ic + δt: ∂a = ūᵀ[n_ci]× δφ, ∂b = −n_wᵀR_i δt
    const Eigen::Vector3d n_ci = g.Ric.transpose() * g.Ri.transpose() * n_w;
    Eigen::Matrix<double, 1, 6> J;
    J.leftCols<3>() = a_b2 * n_w.transpose() * g.Ri;
    J.rightCols<3>() = u.transpose() * hat(n_ci) / b;
    *J_mount += d_rho * J;
  }
  // ∂a/∂n = ray_wᵀ, ∂b/∂n = −p_wciᵀ
  if (J_normal) *J_normal = d_rho * (ray_w.transpose() / b + a_b2 * p_wci.transpose());
  if (J_distance) *J_distance = -a_b2 * d_rho;
  return true;
}

bool HomographyResidual::Evaluate(double const* const* x, double* residuals,
                                  double** jacobians) const {
  const TwoViewPoses poses(x[0], x[1], x[2]);
  TangentJacobian J[3];
  Eigen::Matrix<double, 2, 3> J_normal;
  Eigen::Vector2d r, J_distance;
  const auto wanted = [&](int k) { return jacobians && jacobians[k]; };
  if (!homographyInTangent(poses, Eigen::Map<const Eigen::Vector3d>(x[3]), x[4][0], u_i_, u_j_,
                           sqrt_info_, r, wanted(0) ? &J[0] : nullptr, wanted(1) ? &J[1] : nullptr,
                           wanted(2) ? &J[2] : nullptr, wanted(3) ? &J_normal : nullptr,
                           wanted(4) ? &J_distance : nullptr))
    return false;
  Eigen::Map<Eigen::Vector2d>{residuals} = r;
  if (!jacobians) return true;
  writeAmbientPoseJacobians(J, x, jacobians);
  if (jacobians[3])
    Eigen::Map<Eigen::Matrix<double, 2, 3, Eigen::RowMajor>>{jacobians[3]} = J_normal;
  if (jacobians[4]) Eigen::Map<Eigen::Vector2d>{jacobians[4]} = J_distance;
  return true;
}

}  // namespace rpvio
