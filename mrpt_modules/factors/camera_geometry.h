#pragma once
// Camera poses from body poses and the camera mount, templated for Ceres autodiff.
// Pose blocks: [p, q (x y z w)] as in parameter_blocks.h.
#include <Eigen/Geometry>

namespace rpvio {

template <typename T>
struct RigidTransform {
  Eigen::Matrix<T, 3, 3> R;
  Eigen::Matrix<T, 3, 1> t;
  Eigen::Matrix<T, 3, 1> apply(const Eigen::Matrix<T, 3, 1>& x) const { return R * x + t; }
  RigidTransform inverse() const { return {R.transpose(), -(R.transpose() * t)}; }
  RigidTransform operator*(const RigidTransform& o) const { return {R * o.R, R * o.t + t}; }
};

template <typename T>
RigidTransform<T> transformFromBlock(const T* pose) {
  const Eigen::Quaternion<T> q(pose[6], pose[3], pose[4], pose[5]);
  return {q.normalized().toRotationMatrix(), Eigen::Matrix<T, 3, 1>(pose[0], pose[1], pose[2])};
}

/// T_WC = T_WB · T_BC.
template <typename T>
RigidTransform<T> cameraInWorld(const T* body_pose, const T* T_BC) {
  return transformFromBlock(body_pose) * transformFromBlock(T_BC);
}

}  // namespace rpvio
