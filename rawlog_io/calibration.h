#pragma once
// Reading and writing the sensor calibration of a dataset (`calib.ini` beside each rawlog,
// DESIGN.md §4).
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
#include <string>

#include "common/sensor_types.h"

namespace rpvio {

/// Throws InputError (file + key) on a missing file, a missing key or an unparsable value.
Calibration loadCalibration(const std::string& path);
/// Writes to a temporary name and renames it when complete.
void saveCalibration(const std::string& path, const Calibration& calibration);

/// The rotation nearest to `R` (Frobenius): a matrix printed with few digits made orthonormal.
Eigen::Matrix3d nearestRotation(const Eigen::Matrix3d& R);

/// IMU noise in the figures of VINS-Mono-style configurations (acc_n, gyr_n, acc_w, gyr_w, which
/// they call discrete-time standard deviations, for samples at `rate_hz`) as the densities of
/// calib.ini that give this program's preintegration the covariance VINS-Mono's midpoint
/// propagation gets from them. Per step of Δt = 1 / rate_hz VINS-Mono adds (Δt/2)² acc_n² for each
/// of the step's two samples to the velocity and Δt² acc_w² to the bias; here σ_c² Δt and σ_rw² Δt
/// (imu_preintegration.cpp). Hence σ_c = acc_n √(Δt/2) and σ_rw = acc_w √Δt (docs/datasets.md).
ImuNoise imuNoiseFromVinsMono(double acc_n, double gyr_n, double acc_w, double gyr_w,
                              double rate_hz, double gravity);

}  // namespace rpvio
