#pragma once
// Layout of the Ceres parameter blocks shared by the IMU, vision and homography factors, the
// initializer's bundle adjustment and the sliding-window estimator.
//
//   pose         double[7]  [px py pz qx qy qz qw]: body (IMU) pose in the world frame, Hamilton
//                           unit quaternion in Eigen's coeffs() order; manifold R^3 x
//                           EigenQuaternion. The camera-IMU extrinsic T_BC uses the same layout
//                           (camera in body).
//   speed_bias   double[9]  [vx vy vz bax bay baz bgx bgy bgz]: world-frame velocity, biases.
//   inv_depth    double[1]  1/z of a feature in the camera frame of its first observation.
//   plane        normal double[3] on the unit sphere (ceres::SphereManifold<3>) and distance
//                double[1], world frame: points X on the plane satisfy n·X = d.
//   time_offset  double[1]  td with t_imu = t_cam + td.
#include <Eigen/Geometry>
#include <algorithm>

namespace rpvio {

constexpr int kPoseSize = 7;
constexpr int kPoseLocalSize = 6;
constexpr int kSpeedBiasSize = 9;
constexpr int kPlaneNormalSize = 3;

inline Eigen::Vector3d posePosition(const double* pose) {
  return Eigen::Vector3d(pose[0], pose[1], pose[2]);
}
inline Eigen::Quaterniond poseRotation(const double* pose) {
  return Eigen::Quaterniond(pose[6], pose[3], pose[4], pose[5]);
}
/// The pose block as a rigid transform (its quaternion normalized).
inline Eigen::Isometry3d poseIsometry(const double* pose) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = poseRotation(pose).normalized().toRotationMatrix();
  T.translation() = posePosition(pose);
  return T;
}
/// Writes a rigid transform into a pose block.
inline void setPoseBlock(const Eigen::Isometry3d& T, double* pose) {
  const Eigen::Quaterniond q(T.linear());
  const double p[7] = {
      T.translation().x(), T.translation().y(), T.translation().z(), q.x(), q.y(), q.z(), q.w()};
  std::copy(p, p + 7, pose);
}

}  // namespace rpvio
