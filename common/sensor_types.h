#pragma once
// The sensor and trajectory types every layer shares (DESIGN.md §4): IMU samples, stamped body
// poses, camera intrinsics, IMU noise and the calibration of a dataset. Standard library and Eigen
// only; reading and writing them is rawlog_io's job.
#include <Eigen/Geometry>
#include <array>
#include <cstdio>
#include <string>
#include <vector>

#include "common/options.h"

namespace rpvio {

struct ImuSample {
  double t = 0;                                     // seconds
  Eigen::Vector3d gyro = Eigen::Vector3d::Zero();   // rad/s, body frame
  Eigen::Vector3d accel = Eigen::Vector3d::Zero();  // specific force, m/s^2, body frame
};

/// Body pose in the world frame at time t.
struct StampedPose {
  double t = 0;  // seconds; KITTI poses get their index as stamp
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
};
using Trajectory = std::vector<StampedPose>;

enum class DistortionModel { None, RadTan, Equidistant };

struct CameraIntrinsics {
  int width = 0, height = 0;
  double fx = 0, fy = 0, cx = 0, cy = 0;
  DistortionModel model = DistortionModel::None;
  std::array<double, 4> distortion{0, 0, 0, 0};  // radtan: k1 k2 p1 p2; equidistant: k1..k4
};

struct ImuNoise {
  double gyro_noise_density = 1.7e-4;   // rad/s/sqrt(Hz)
  double accel_noise_density = 2.0e-3;  // m/s^2/sqrt(Hz)
  double gyro_random_walk = 1.9e-5;     // rad/s^2/sqrt(Hz)
  double accel_random_walk = 3.0e-3;    // m/s^3/sqrt(Hz)
  double rate_hz = 200.0;
  double gravity = 9.81;  // m/s^2, magnitude

  template <class Visitor>
  void fields(Visitor& v) {
    RPVIO_OPTION(v, rate_hz);
    RPVIO_OPTION(v, gyro_noise_density);
    RPVIO_OPTION(v, accel_noise_density);
    RPVIO_OPTION(v, gyro_random_walk);
    RPVIO_OPTION(v, accel_random_walk);
    RPVIO_OPTION(v, gravity);
  }
};

/// A dataset's calibration (calib.ini, rawlog_io/calibration.h reads and writes it).
struct Calibration {
  CameraIntrinsics camera;
  Eigen::Isometry3d T_BC = Eigen::Isometry3d::Identity();  // camera pose in the body frame
  double time_offset = 0.0;                                // t_imu = t_cam + time_offset
  ImuNoise imu;
  double camera_height =
      0.0;  // m, the camera's height above a flat ground (robots, cars); 0: unknown
};

/// A stamp in seconds for the output files, in full: "1403715273.262142976" (9 decimals, the
/// nanoseconds of a rawlog's stamps), not "1.4e+09".
inline std::string stampText(double t) {
  char text[40];
  std::snprintf(text, sizeof text, "%.9f", t);
  return text;
}

/// A time in seconds for log lines, in full: "1403715273.262 s", not "1.4e+09 s".
inline std::string timeText(double t) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f s", t);
  return text;
}

}  // namespace rpvio
