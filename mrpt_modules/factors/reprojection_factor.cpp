#include "mrpt_modules/factors/reprojection_factor.h"

#include <Eigen/Geometry>

#include "mrpt_modules/factors/parameter_blocks.h"
#include "mrpt_modules/factors/pose_manifold.h"
#include "mrpt_modules/imu/so3.h"

namespace rpvio {

bool ReprojectionResidual::Evaluate(double const* const* x, double* residuals,
                                    double** jacobians) const {
  const Eigen::Vector3d Pi = posePosition(x[0]), Pj = posePosition(x[1]), tic = posePosition(x[2]);
  const Eigen::Matrix3d Ri = poseRotation(x[0]).normalized().toRotationMatrix();
  const Eigen::Matrix3d Rj = poseRotation(x[1]).normalized().toRotationMatrix();
  const Eigen::Matrix3d Ric = poseRotation(x[2]).normalized().toRotationMatrix();
  const double rho = x[3][0];
  const Eigen::Vector3d X_ci = Eigen::Vector3d(u_i_.x(), u_i_.y(), 1) / rho;
  const Eigen::Vector3d X_bi = Ric * X_ci + tic;
  const Eigen::Vector3d X_w = Ri * X_bi + Pi;
  const Eigen::Vector3d X_bj = Rj.transpose() * (X_w - Pj);
  const Eigen::Vector3d X_cj = Ric.transpose() * (X_bj - tic);
  const double z = X_cj.z();
  Eigen::Map<Eigen::Vector2d> r(residuals);
  r = sqrt_info_ * (X_cj.head<2>() / z - u_j_);
  if (!jacobians) return true;

  // d r / d X_cj.
  Eigen::Matrix<double, 2, 3> reduce;
  reduce << 1 / z, 0, -X_cj.x() / (z * z), 0, 1 / z, -X_cj.y() / (z * z);
  reduce *= sqrt_info_;
  const Eigen::Matrix3d Rcj_w = Ric.transpose() * Rj.transpose();
  if (jacobians[0]) {  // X_w = Ri Exp(δθ) X_bi + Pi + δp
    Eigen::Matrix<double, 3, 6> J;
    J.leftCols<3>() = Rcj_w;
    J.rightCols<3>() = -Rcj_w * Ri * hat(X_bi);
    Eigen::Map<Eigen::Matrix<double, 2, 7, Eigen::RowMajor>> J_amb(jacobians[0]);
    J_amb = tangentToAmbient<2>(reduce * J, x[0]);
  }
  if (jacobians[1]) {  // X_bj = (Rj Exp(δθ))ᵀ (X_w − Pj − δp)
    Eigen::Matrix<double, 3, 6> J;
    J.leftCols<3>() = -Rcj_w;
    J.rightCols<3>() = Ric.transpose() * hat(X_bj);
    Eigen::Map<Eigen::Matrix<double, 2, 7, Eigen::RowMajor>> J_amb(jacobians[1]);
    J_amb = tangentToAmbient<2>(reduce * J, x[1]);
  }
  if (jacobians[2]) {  // the mount enters on both sides: T_BC⁻¹ (T_WBj⁻¹ T_WBi) T_BC
    const Eigen::Matrix3d R_ji = Rj.transpose() * Ri;
    Eigen::Matrix<double, 3, 6> J;
    J.leftCols<3>() = Ric.transpose() * (R_ji - Eigen::Matrix3d::Identity());
    const Eigen::Matrix3d A = Ric.transpose() * R_ji * Ric;
    J.rightCols<3>() = -A * hat(X_ci) + hat(A * X_ci) +
                       hat(Ric.transpose() * (Rj.transpose() * (Ri * tic + Pi - Pj) - tic));
    Eigen::Map<Eigen::Matrix<double, 2, 7, Eigen::RowMajor>> J_amb(jacobians[2]);
    J_amb = tangentToAmbient<2>(reduce * J, x[2]);
  }
  if (jacobians[3]) {
    const Eigen::Vector3d d = Rcj_w * Ri * Ric * (-X_ci / rho);  // d X_cj / d ρ
    Eigen::Map<Eigen::Vector2d> J_rho(jacobians[3]);
    J_rho = reduce * d;
  }
  return true;
}

}  // namespace rpvio
