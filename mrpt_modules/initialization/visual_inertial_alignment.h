#pragma once
// Visual-inertial alignment (Qin et al. 2018, VINS-Mono §V-B, written anew): given the camera
// trajectory of the first frames up to scale, in the frame of the first camera c0, and the IMU
// preintegrations between them, recover the gyroscope bias, the metric scale, gravity in c0 and
// every frame's velocity.
#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mrpt_modules/imu/imu_preintegration.h"

namespace rpvio {

struct UpToScaleFrame {
  Eigen::Matrix3d R_c0_c;                            // camera orientation in c0
  Eigen::Vector3d p_c0_c;                            // camera position in c0, arbitrary scale
  std::shared_ptr<ImuPreintegration> from_previous;  // IMU from the previous frame (null for 0)
};

struct AlignmentResult {
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_bias = Eigen::Vector3d::Zero();  // change from the preintegrations' own
  double scale = 0;                                      // metric = scale * p_c0_c
  // Standard deviation of the scale (residual variance times (AᵀA)⁻¹ of the final linear system):
  // large when the window's accelerations do not make the scale observable.
  double scale_sigma = 0;
  Eigen::Vector3d gravity_c0 = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> velocity_c0;  // body velocity of each frame, c0 frame
};

/// Gyro bias by least squares on the rotations between consecutive frames; repropagates the
/// preintegrations with it. `T_BC`: camera in body.
Eigen::Vector3d solveGyroBias(std::vector<UpToScaleFrame>& frames, const Eigen::Isometry3d& T_BC);

/// Full alignment; on failure (negative scale, gravity magnitude far from `gravity`), nullopt and
/// the reason in `why_not`. With `known_scale` (metres per unit of p_c0_c, e.g. from the camera's
/// height above the ground plane) the scale is not solved for: scale_sigma is 0. With
/// `first_velocity_c0` (the first frame's body velocity in c0, known from elsewhere, e.g. dead
/// reckoning from the state before a reset), v_0 = v_c0 enters as three more equations, weighted
/// as the IMU's velocity equations are: the scale then needs no excitation.
std::optional<AlignmentResult> alignVisualInertial(
    std::vector<UpToScaleFrame>& frames, const Eigen::Isometry3d& T_BC, double gravity,
    std::string* why_not = nullptr, std::optional<double> known_scale = {},
    const std::optional<Eigen::Vector3d>& first_velocity_c0 = {});

}  // namespace rpvio
