#pragma once
// Inverse-depth reprojection factor (VINS-Mono §IV-C): a feature first seen at normalized point
// u_i in frame i, with inverse depth ρ in camera i, observed at u_j in frame j.
// Blocks: pose_i [7], pose_j [7], T_BC [7], inverse depth [1]. Residual: 2, normalized
// coordinates scaled by sqrt_info = focal / sigma_px (same weight as the homography factor).
#include <ceres/autodiff_cost_function.h>
#include <Eigen/Core>

#include "mrpt_modules/factors/camera_geometry.h"

namespace rpvio {

struct ReprojectionResidual {
  ReprojectionResidual(const Eigen::Vector2d& u_i, const Eigen::Vector2d& u_j, double sqrt_info)
      : u_i(u_i), u_j(u_j), sqrt_info(sqrt_info) {}

  template <typename T>
  bool operator()(const T* pose_i, const T* pose_j, const T* T_BC, const T* inv_depth,
                  T* residual) const {
    const Eigen::Matrix<T, 3, 1> X_ci =
        Eigen::Matrix<T, 3, 1>(T(u_i.x()), T(u_i.y()), T(1)) / inv_depth[0];
    const Eigen::Matrix<T, 3, 1> X_w = cameraInWorld(pose_i, T_BC).apply(X_ci);
    const Eigen::Matrix<T, 3, 1> X_cj = cameraInWorld(pose_j, T_BC).inverse().apply(X_w);
    residual[0] = T(sqrt_info) * (X_cj.x() / X_cj.z() - T(u_j.x()));
    residual[1] = T(sqrt_info) * (X_cj.y() / X_cj.z() - T(u_j.y()));
    return true;
  }

  static ceres::CostFunction* create(const Eigen::Vector2d& u_i, const Eigen::Vector2d& u_j,
                                     double sqrt_info) {
    return new ceres::AutoDiffCostFunction<ReprojectionResidual, 2, 7, 7, 7, 1>(
        new ReprojectionResidual(u_i, u_j, sqrt_info));
  }

  Eigen::Vector2d u_i, u_j;
  double sqrt_info;
};

}  // namespace rpvio
