#pragma once
// Inverse-depth reprojection factor (VINS-Mono §IV-C): a feature first seen at normalized point
// u_i in frame i, with inverse depth ρ in camera i, observed at u_j in frame j:
//   X_cj = T_BC⁻¹ T_WBj⁻¹ T_WBi T_BC (ū_i / ρ),   r = sqrt_info (π(X_cj) − u_j).
// Blocks: pose_i [7], pose_j [7], T_BC [7], inverse depth [1]; residual 2 in normalized
// coordinates scaled by sqrt_info = focal / sigma_px (the same weight as the homography factor).
// Analytic Jacobians in the tangent space of the poses (right perturbation, pose_manifold.h),
// lifted to the 7 ambient numbers.
#include <ceres/sized_cost_function.h>
#include <Eigen/Core>

namespace rpvio {

using TangentJacobian = Eigen::Matrix<double, 2, 6>;  // of a 2-row residual, a pose's tangent

/// The two body poses and the mount of a two-view residual, as rotations and positions.
struct TwoViewPoses {
  TwoViewPoses(const double* pose_i, const double* pose_j, const double* mount);
  Eigen::Matrix3d Ri, Rj, Ric, Rcj_w;  // Rcj_w = (Rj Ric)ᵀ
  Eigen::Vector3d Pi, Pj, tic;
};

/// The reprojection residual of u_i at inverse depth ρ into frame j and its Jacobians in the
/// poses' tangent spaces (each skipped when nullptr).
void reprojectionInTangent(const TwoViewPoses& poses, const Eigen::Vector2d& u_i,
                           const Eigen::Vector2d& u_j, double sqrt_info, double rho,
                           Eigen::Vector2d& residual, TangentJacobian* J_pose_i,
                           TangentJacobian* J_pose_j, TangentJacobian* J_mount,
                           Eigen::Vector2d* J_rho);

/// Writes the tangent Jacobians J of a 2-row residual's pose blocks 0–2 (pose_i, pose_j, T_BC)
/// into Ceres' ambient ones, for the blocks it wants (jacobians non-null).
void writeAmbientPoseJacobians(const TangentJacobian (&J)[3], double const* const* x,
                               double** jacobians);

class ReprojectionResidual : public ceres::SizedCostFunction<2, 7, 7, 7, 1> {
 public:
  ReprojectionResidual(const Eigen::Vector2d& u_i, const Eigen::Vector2d& u_j, double sqrt_info)
      : u_i_(u_i), u_j_(u_j), sqrt_info_(sqrt_info) {}
  static ceres::CostFunction* create(const Eigen::Vector2d& u_i, const Eigen::Vector2d& u_j,
                                     double sqrt_info) {
    return new ReprojectionResidual(u_i, u_j, sqrt_info);
  }
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  Eigen::Vector2d u_i_, u_j_;
  double sqrt_info_;
};

}  // namespace rpvio
