#pragma once
// EuRoC (ASL) CSV files: IMU samples and full ground-truth states (with velocity and biases).
// Errors name the file and the line (InputError).
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "common/sensor_types.h"

namespace rpvio {

/// `imu0/data.csv`: t [ns], w_x, w_y, w_z [rad/s], a_x, a_y, a_z [m/s^2]; strictly increasing t.
std::vector<ImuSample> readEurocImuCsv(const std::string& path);

struct EurocStateSample {
  double t = 0;
  Eigen::Vector3d p, v, gyro_bias, accel_bias;
  Eigen::Quaterniond q;
};

/// `state_groundtruth_estimate0/data.csv` (or `gt0/data.csv`): t, p, q (w x y z), v, b_w, b_a.
std::vector<EurocStateSample> readEurocStateCsv(const std::string& path);

}  // namespace rpvio
