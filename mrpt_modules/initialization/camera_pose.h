#pragma once
// A camera pose in the initializer's reference frame r (the first camera of the chosen frame pair
// for the SfM, camera 0 for the alignment): X_r = R_r_c X_c + p_r_c.
#include <Eigen/Geometry>

namespace rpvio {

struct CameraPose {
  Eigen::Matrix3d R_r_c = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p_r_c = Eigen::Vector3d::Zero();

  Eigen::Vector3d toCamera(const Eigen::Vector3d& X_r) const {
    return R_r_c.transpose() * (X_r - p_r_c);
  }
  Eigen::Vector3d toReference(const Eigen::Vector3d& X_c) const { return R_r_c * X_c + p_r_c; }
};

}  // namespace rpvio
