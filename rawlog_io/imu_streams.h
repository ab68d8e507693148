#pragma once
// IMU streams as datasets deliver them: a gyroscope and an accelerometer sampled apart (OpenLORIS'
// D435i, ADVIO's iPhone) made one stream, and a fast IMU thinned to the rate the estimator expects.
#include <vector>

#include "common/sensor_types.h"

namespace rpvio {

/// One stream from a gyroscope's and an accelerometer's separate samples (only their `gyro`,
/// resp. `accel`, is read): at every sample of either sensor within the time both cover, the
/// other sensor's value interpolated linearly.
std::vector<ImuSample> mergeSplitImu(const std::vector<ImuSample>& gyro,
                                     const std::vector<ImuSample>& accel);

/// The samples decimated to `rate_hz` by timestamp: the first sample at or after each point of
/// the grid t0 + k / rate is kept (a thousandth of a period early counts as on it: stamp
/// rounding). rate_hz <= 0: all.
std::vector<ImuSample> decimateImu(const std::vector<ImuSample>& samples, double rate_hz);

/// The median of the vectors' norms (0 for none): an accelerometer's is about gravity in m/s^2
/// whatever the motion, which tells the units of a stream.
double medianNorm(const std::vector<Eigen::Vector3d>& vectors);

}  // namespace rpvio
