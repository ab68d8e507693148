#include "mrpt_modules/factors/camera_height_factor.h"

#include <Eigen/Geometry>

#include "mrpt_modules/factors/parameter_blocks.h"
#include "mrpt_modules/factors/pose_manifold.h"
#include "mrpt_modules/imu/so3.h"

namespace rpvio {

bool CameraHeightResidual::Evaluate(double const* const* parameters, double* residuals,
                                    double** jacobians) const {
  const double* pose = parameters[0];
  const double* mount = parameters[1];
  const Eigen::Map<const Eigen::Vector3d> n(parameters[2]);
  const double d = parameters[3][0];
  const Eigen::Matrix3d R = poseRotation(pose).normalized().toRotationMatrix();
  const Eigen::Vector3d t_BC = posePosition(mount);
  const Eigen::Vector3d c = posePosition(pose) + R * t_BC;
  const double w = sqrt_info_ * side_;
  residuals[0] = w * (n.dot(c) - d) - sqrt_info_ * height_;
  if (!jacobians) return true;
  if (jacobians[0]) {
    Eigen::Matrix<double, 1, 6> J;
    J.head<3>() = w * n.transpose();
    J.tail<3>() = -w * n.transpose() * R * hat(t_BC);
    Eigen::Map<Eigen::Matrix<double, 1, 7>> J_pose(jacobians[0]);
    J_pose = tangentToAmbient<1>(J, pose);
  }
  if (jacobians[1]) {
    Eigen::Matrix<double, 1, 6> J = Eigen::Matrix<double, 1, 6>::Zero();
    J.head<3>() = w * n.transpose() * R;
    Eigen::Map<Eigen::Matrix<double, 1, 7>> J_mount(jacobians[1]);
    J_mount = tangentToAmbient<1>(J, mount);
  }
  if (jacobians[2]) Eigen::Map<Eigen::RowVector3d>{jacobians[2]} = w * c.transpose();
  if (jacobians[3]) jacobians[3][0] = -w;
  return true;
}

}  // namespace rpvio
