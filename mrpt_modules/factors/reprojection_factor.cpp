#include "mrpt_modules/factors/reprojection_factor.h"

#include <Eigen/Geometry>

#include "mrpt_modules/factors/parameter_blocks.h"
#include "mrpt_modules/factors/pose_manifold.h"
#include "mrpt_modules/imu/so3.h"

namespace rpvio {

TwoViewPoses::TwoViewPoses(const double* pose_i, const double* pose_j, const double* mount)
    : Ri(poseRotation(pose_i).normalized().toRotationMatrix()),
      Rj(poseRotation(pose_j).normalized().toRotationMatrix()),
      Ric(poseRotation(mount).normalized().toRotationMatrix()),
      Rcj_w(Ric.transpose() * Rj.transpose()),
      Pi(posePosition(pose_i)),
      Pj(posePosition(pose_j)),
      tic(posePosition(mount)) {}

void reprojectionInTangent(const TwoViewPoses& g, const Eigen::Vector2d& u_i,
                           const Eigen::Vector2d& u_j, double sqrt_info, double rho,
                           Eigen::Vector2d& residual, TangentJacobian* J_pose_i,
                           TangentJacobian* J_pose_j, TangentJacobian* J_mount,
                           Eigen::Vector2d* J_rho) {
  const Eigen::Vector3d X_ci = Eigen::Vector3d(u_i.x(), u_i.y(), 1) / rho;
  const Eigen::Vector3d X_bi = g.Ric * X_ci + g.tic;
  const Eigen::Vector3d X_w = g.Ri * X_bi + g.Pi;
  const Eigen::Vector3d X_bj = g.Rj.transpose() * (X_w - g.Pj);
  const Eigen::Vector3d X_cj = g.Ric.transpose() * (X_bj - g.tic);
  const double z = X_cj.z();
  residual = sqrt_info * (X_cj.head<2>() / z - u_j);
  if (!J_pose_i && !J_pose_j && !J_mount && !J_rho) return;

  // d r / d X_cj.
  Eigen::Matrix<double, 2, 3> reduce;
  reduce << 1 / z, 0, -X_cj.x() / (z * z), 0, 1 / z, -X_cj.y() / (z * z);
  reduce *= sqrt_info;
  if (J_pose_i) {  // X_w = Ri Exp(δθ) X_bi + Pi + δp
    Eigen::Matrix<double, 3, 6> J;
    J.leftCols<3>() = g.Rcj_w;
    J.rightCols<3>() = -g.Rcj_w * g.Ri * hat(X_bi);
    *J_pose_i = reduce * J;
  }
  if (J_pose_j) {  // X_bj = (Rj Exp(δθ))ᵀ (X_w − Pj − δp)
    Eigen::Matrix<double, 3, 6> J;
    J.leftCols<3>() = -g.Rcj_w;
    J.rightCols<3>() = g.Ric.transpose() * hat(X_bj);
    *J_pose_j = reduce * J;
  }
  if (J_mount) {  // the mount enters on both sides: T_BC⁻¹ (T_WBj⁻¹ T_WBi) T_BC
    const Eigen::Matrix3d R_ji = g.Rj.transpose() * g.Ri;
    Eigen::Matrix<double, 3, 6> J;
    J.leftCols<3>() = g.Ric.transpose() * (R_ji - Eigen::Matrix3d::Identity());
    const Eigen::Matrix3d A = g.Ric.transpose() * R_ji * g.Ric;
    J.rightCols<3>() =
        -A * hat(X_ci) + hat(A * X_ci) +
        hat(g.Ric.transpose() * (g.Rj.transpose() * (g.Ri * g.tic + g.Pi - g.Pj) - g.tic));
    *J_mount = reduce * J;
  }
  if (J_rho) *J_rho = reduce * (g.Rcj_w * g.Ri * g.Ric * (-X_ci / rho));  // d X_cj / d ρ
}

void writeAmbientPoseJacobians(const TangentJacobian (&J)[3], double const* const* x,
                               double** jacobians) {
  for (int k = 0; k < 3; ++k)
    if (jacobians[k])
      Eigen::Map<Eigen::Matrix<double, 2, 7, Eigen::RowMajor>>{jacobians[k]} =
          tangentToAmbient<2>(J[k], x[k]);
}

bool ReprojectionResidual::Evaluate(double const* const* x, double* residuals,
                                    double** jacobians) const {
  const TwoViewPoses poses(x[0], x[1], x[2]);
  TangentJacobian J[3];
  Eigen::Vector2d r, J_rho;
  const auto wanted = [&](int k) { return jacobians && jacobians[k]; };
  reprojectionInTangent(poses, u_i_, u_j_, sqrt_info_, x[3][0], r, wanted(0) ? &J[0] : nullptr,
                        wanted(1) ? &J[1] : nullptr, wanted(2) ? &J[2] : nullptr,
                        wanted(3) ? &J_rho : nullptr);
  Eigen::Map<Eigen::Vector2d>{residuals} = r;
  if (!jacobians) return true;
  if (jacobians[3]) Eigen::Map<Eigen::Vector2d>{jacobians[3]} = J_rho;
  writeAmbientPoseJacobians(J, x, jacobians);
  return true;
}

}  // namespace rpvio
