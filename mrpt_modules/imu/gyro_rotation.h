#pragma once
// The body's rotation over a time interval from gyroscope samples alone (no preintegration
// state): for the time-offset fit and the front-end's rotation prediction.
#include <Eigen/Geometry>
#include <vector>

#include "common/sensor_types.h"

namespace rpvio {

/// ΔR from time a to time b (a ≤ b): Π Exp((ω(τ) − bias) δτ) over the samples' intervals, the rate
/// at each piece's midpoint linear between samples (held constant outside them). `samples` in
/// time order, not empty.
Eigen::Matrix3d gyroRotation(const std::vector<ImuSample>& samples, double a, double b,
                             const Eigen::Vector3d& bias);

/// The camera's rotation from time a to b, previous-camera coordinates to current ones:
/// R_BCᵀ ΔR_bᵀ R_BC with ΔR_b = gyroRotation(samples, a, b, 0) (bias not corrected).
Eigen::Matrix3d cameraRotationBetween(const std::vector<ImuSample>& samples, double a, double b,
                                      const Eigen::Matrix3d& R_BC);

}  // namespace rpvio
