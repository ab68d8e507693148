#pragma once
// RP-VIO's planar homography factor (Ram et al. 2021, Eq. 6): a feature of a plane seen at
// normalized point u_i in frame i and u_j in frame j must satisfy u_j = π(H_ji ū_i), with
//   H_ji = R_ji + t_ji n_ciᵀ / d_ci,                                        (plane-induced
//   homography)
// the camera motion X_cj = R_ji X_ci + t_ji from the body poses and the mount T_BC, and the plane
// n·X = d given in the world frame and moved to camera i: n_ci = R_wciᵀ n_w, d_ci = d_w −
// n_w·p_wci.
//
// Weight: upstream RP-VIO leaves this residual unweighted (information 1 in normalized units)
// while its reprojection factor is weighted focal/1.5 px. Here both use the same sqrt_info
// (visionSqrtInfo(focal, sigma_px), default 460/1.5): the two residuals measure the same thing,
// an image error, so they get the same unit and the same robust-loss scale.
// Blocks: pose_i [7], pose_j [7], T_BC [7] (may be held constant), plane normal [3] (unit,
// ceres::SphereManifold<3>), plane distance [1]. Residual: 2.
#include <ceres/sized_cost_function.h>
#include <Eigen/Core>

#include "mrpt_modules/factors/camera_geometry.h"
#include "mrpt_modules/factors/reprojection_factor.h"

namespace rpvio {

/// sqrt of the information of a normalized-coordinate residual whose pixel noise is sigma_px at
/// focal length `focal_px`: 1 unit of residual = sigma_px pixels.
double visionSqrtInfo(double focal_px = 460.0, double sigma_px = 1.5);

/// H_ji (x_cj ~ H x_ci) of the plane n_w·X = d_w for the camera poses T_w_ci, T_w_cj.
template <typename T>
Eigen::Matrix<T, 3, 3> planeInducedHomography(const RigidTransform<T>& W_ci,
                                              const RigidTransform<T>& W_cj,
                                              const Eigen::Matrix<T, 3, 1>& n_w, const T& d_w) {
  const RigidTransform<T> cj_ci = W_cj.inverse() * W_ci;
  const Eigen::Matrix<T, 3, 1> n_ci = W_ci.R.transpose() * n_w;
  const T d_ci = d_w - n_w.dot(W_ci.t);
  return cj_ci.R + cj_ci.t * n_ci.transpose() / d_ci;
}

/// The homography residual of the feature (u_i, u_j) and its Jacobians: the poses' and the mount's
/// in their tangent spaces, the normal's w.r.t. its 3 ambient numbers (each skipped when nullptr).
/// False where it is not defined (the ray of u_i parallel to the plane, or camera i on it).
bool homographyInTangent(const TwoViewPoses& poses, const Eigen::Vector3d& n_w, double d_w,
                         const Eigen::Vector2d& u_i, const Eigen::Vector2d& u_j, double sqrt_info,
                         Eigen::Vector2d& residual, TangentJacobian* J_pose_i,
                         TangentJacobian* J_pose_j, TangentJacobian* J_mount,
                         Eigen::Matrix<double, 2, 3>* J_normal, Eigen::Vector2d* J_distance);

/// The residual is the reprojection (reprojection_factor.h) of the point where the ray of u_i meets
/// the plane — X_ci = ū_i / ρ with ρ = (n_ci·ū_i) / d_ci, since H_ji ū_i = ρ X_cj — so its
/// Jacobians are the reprojection factor's, plus its inverse-depth column times ∂ρ/∂(pose_i,
/// T_BC, n_w, d_w) (analytic; ambient Jacobians for the normal).
class HomographyResidual : public ceres::SizedCostFunction<2, 7, 7, 7, 3, 1> {
 public:
  HomographyResidual(const Eigen::Vector2d& u_i, const Eigen::Vector2d& u_j, double sqrt_info)
      : u_i_(u_i), u_j_(u_j), sqrt_info_(sqrt_info) {}
  /// The caller owns it.
  static ceres::CostFunction* create(const Eigen::Vector2d& u_i, const Eigen::Vector2d& u_j,
                                     double sqrt_info) {
    return new HomographyResidual(u_i, u_j, sqrt_info);
  }
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  Eigen::Vector2d u_i_, u_j_;
  double sqrt_info_;
};

}  // namespace rpvio
