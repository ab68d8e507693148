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

/// IMU noise given as discrete-time standard deviations per sample at `rate_hz` (the acc_n,
/// gyr_n, acc_w, gyr_w of VINS-Mono-style configurations) as the continuous-time densities of
/// calib.ini, Δt = 1 / rate_hz: white noise σ_c = σ_d √Δt, bias random walk σ_rw = σ_w / √Δt
/// (Kalibr's convention; docs/datasets.md).
ImuNoise imuNoiseFromDiscrete(double acc_n, double gyr_n, double acc_w, double gyr_w,
                              double rate_hz, double gravity);

}  // namespace rpvio
