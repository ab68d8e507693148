#pragma once
// RP-VIO's planar homography factor (Ram et al. 2021, Eq. 6): a feature of a plane seen at
// normalized point u_i in frame i and u_j in frame j must satisfy u_j = π(H_ji ū_i), with
//   H_ji = R_ji + t_ji n_ciᵀ / d_ci,
// the camera motion (X_cj = R_ji X_ci + t_ji) from the body poses and the mount T_BC, and the
// plane n·X = d given in the world frame and moved to camera i. Unlike upstream RP-VIO, which
// leaves this residual unweighted, it is weighted like the reprojection factor (focal / sigma_px),
// so both speak in the same units of image error.
// Blocks: pose_i [7], pose_j [7], T_BC [7], plane normal [3] (unit, SphereManifold), distance [1].
#include <ceres/autodiff_cost_function.h>
#include <Eigen/Core>

#include "mrpt_modules/factors/camera_geometry.h"

namespace rpvio {

struct HomographyResidual {
  HomographyResidual(const Eigen::Vector2d& u_i, const Eigen::Vector2d& u_j, double sqrt_info)
      : u_i(u_i), u_j(u_j), sqrt_info(sqrt_info) {}

  template <typename T>
  bool operator()(const T* pose_i, const T* pose_j, const T* T_BC, const T* normal_w,
                  const T* distance_w, T* residual) const {
    const RigidTransform<T> W_ci = cameraInWorld(pose_i, T_BC), W_cj = cameraInWorld(pose_j, T_BC);
    const RigidTransform<T> cj_ci = W_cj.inverse() * W_ci;
    const Eigen::Matrix<T, 3, 1> n_w(normal_w[0], normal_w[1], normal_w[2]);
    const Eigen::Matrix<T, 3, 1> n_ci = W_ci.R.transpose() * n_w;
    const T d_ci = distance_w[0] - n_w.dot(W_ci.t);
    const Eigen::Matrix<T, 3, 3> H = cj_ci.R + cj_ci.t * n_ci.transpose() / d_ci;
    const Eigen::Matrix<T, 3, 1> x = H * Eigen::Matrix<T, 3, 1>(T(u_i.x()), T(u_i.y()), T(1));
    residual[0] = T(sqrt_info) * (x.x() / x.z() - T(u_j.x()));
    residual[1] = T(sqrt_info) * (x.y() / x.z() - T(u_j.y()));
    return true;
  }

  static ceres::CostFunction* create(const Eigen::Vector2d& u_i, const Eigen::Vector2d& u_j,
                                     double sqrt_info) {
    return new ceres::AutoDiffCostFunction<HomographyResidual, 2, 7, 7, 7, 3, 1>(
        new HomographyResidual(u_i, u_j, sqrt_info));
  }

  Eigen::Vector2d u_i, u_j;
  double sqrt_info;
};

}  // namespace rpvio
