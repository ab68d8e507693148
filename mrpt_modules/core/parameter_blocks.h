#pragma once
// Layout of the Ceres parameter blocks shared by the IMU, vision and homography factors, the
// initializer's bundle adjustment and the sliding-window estimator.
//
//   pose        double[7]  [px py pz qx qy qz qw]  body (IMU) pose in the world frame, Hamilton
//   unit
//                          quaternion in Eigen's coeffs() order; manifold: R^3 x EigenQuaternion.
//                          The camera-IMU extrinsic T_BC uses the same layout (camera in body).
//   speed_bias  double[9]  [vx vy vz bax bay baz bgx bgy bgz]  world-frame velocity, biases.
//   inv_depth   double[1]  1/z of a feature in the camera frame of its first observation.
//   plane       normal double[3] on the unit sphere (ceres::SphereManifold<3>) + distance
//   double[1],
//               world frame, points X on the plane satisfy n·X = d.
//   time_offset double[1]  td with t_imu = t_cam + td.
#include <Eigen/Geometry>

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

}  // namespace rpvio
