#pragma once
// Inverse-depth reprojection with an unknown camera–IMU time offset td (VINS-Mono's online
// temporal calibration, Qin & Shen 2018, Eq. 12): an image stamped t was taken at IMU time t + td,
// so at the frame's IMU time t a feature is where it was minus its image velocity times td:
//   u(td) = u − td · v            (v: normalized coordinates per second, from the tracker)
// applied to both observations of ReprojectionResidual's model:
//   X_cj = T_BC⁻¹ T_WBj⁻¹ T_WBi T_BC (ū_i(td) / ρ),   r = sqrt_info (π(X_cj) − u_j(td)).
// Blocks: pose_i [7], pose_j [7], T_BC [7], inverse depth [1], td [1] (s); residual 2. Autodiff.
#include <ceres/cost_function.h>
#include <Eigen/Core>

#include "mrpt_modules/factors/camera_geometry.h"

namespace rpvio {

struct TimeOffsetReprojectionResidual {
  TimeOffsetReprojectionResidual(const Eigen::Vector2d& u_i, const Eigen::Vector2d& v_i,
                                 const Eigen::Vector2d& u_j, const Eigen::Vector2d& v_j,
                                 double sqrt_info)
      : u_i(u_i), v_i(v_i), u_j(u_j), v_j(v_j), sqrt_info(sqrt_info) {}

  template <typename T>
  bool operator()(const T* pose_i, const T* pose_j, const T* T_BC, const T* inverse_depth,
                  const T* td, T* residual) const {
    const Eigen::Matrix<T, 2, 1> ui = u_i.cast<T>() - td[0] * v_i.cast<T>();
    const Eigen::Matrix<T, 2, 1> uj = u_j.cast<T>() - td[0] * v_j.cast<T>();
    const Eigen::Matrix<T, 3, 1> X_ci =
        Eigen::Matrix<T, 3, 1>(ui.x(), ui.y(), T(1)) / inverse_depth[0];
    const RigidTransform<T> cj_ci =
        cameraInWorld(pose_j, T_BC).inverse() * cameraInWorld(pose_i, T_BC);
    const Eigen::Matrix<T, 3, 1> X_cj = cj_ci.apply(X_ci);
    residual[0] = T(sqrt_info) * (X_cj.x() / X_cj.z() - uj.x());
    residual[1] = T(sqrt_info) * (X_cj.y() / X_cj.z() - uj.y());
    return true;
  }

  /// Autodiff cost function (2 residuals; blocks 7, 7, 7, 1, 1); the caller owns it.
  static ceres::CostFunction* create(const Eigen::Vector2d& u_i, const Eigen::Vector2d& v_i,
                                     const Eigen::Vector2d& u_j, const Eigen::Vector2d& v_j,
                                     double sqrt_info);

  Eigen::Vector2d u_i, v_i, u_j, v_j;
  double sqrt_info;
};

}  // namespace rpvio
