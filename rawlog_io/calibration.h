#pragma once
// Sensor calibration of a dataset (`calib.ini` beside each rawlog, DESIGN.md §4).
//
// INI layout (all sections required unless noted):
//   [camera]  width, height, fx, fy, cx, cy,
//             distortion_model = none | radtan | equidistant,
//             distortion = k1 k2 p1 p2 (radtan) or k1 k2 k3 k4 (equidistant); absent for none
//   [T_BC]    camera pose in the body (IMU) frame: translation = x y z (m),
//             rotation = qx qy qz qw (Hamilton, unit)
//   [time]    offset = td (s): t_imu = t_cam + td   (optional, default 0)
//   [imu]     gyro_noise_density (rad/s/sqrt(Hz)), accel_noise_density (m/s^2/sqrt(Hz)),
//             gyro_random_walk (rad/s^2/sqrt(Hz)), accel_random_walk (m/s^3/sqrt(Hz)),
//             rate_hz, gravity (m/s^2, magnitude)
#include <Eigen/Geometry>
#include <array>
#include <string>

namespace rpvio {

enum class DistortionModel { None, RadTan, Equidistant };

struct CameraIntrinsics {
  int width = 0, height = 0;
  double fx = 0, fy = 0, cx = 0, cy = 0;
  DistortionModel model = DistortionModel::None;
  std::array<double, 4> distortion{0, 0, 0, 0};  // radtan: k1 k2 p1 p2; equidistant: k1..k4
};

struct ImuNoise {
  double gyro_noise_density = 1.7e-4;
  double accel_noise_density = 2.0e-3;
  double gyro_random_walk = 1.9e-5;
  double accel_random_walk = 3.0e-3;
  double rate_hz = 200.0;
  double gravity = 9.81;
};

struct Calibration {
  CameraIntrinsics camera;
  Eigen::Isometry3d T_BC = Eigen::Isometry3d::Identity();  // camera pose in the body frame
  double time_offset = 0.0;                                // t_imu = t_cam + time_offset
  ImuNoise imu;

  /// Throws InputError (file + key) on a missing file, a missing key or an unparsable value.
  static Calibration load(const std::string& path);
  /// Writes to a temporary name and renames it when complete.
  void save(const std::string& path) const;
};

}  // namespace rpvio
