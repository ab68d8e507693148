#pragma once
// A closed-form back-and-forth translation with smooth reversals: the motion of the simulator's
// moving planar objects, and of the moving planes of groundtruth_planes.yaml.
#include <Eigen/Core>
#include <cmath>

namespace rpvio {

/// offset(t) = amplitude · sin(2π t / period + phase) · axis: between −amplitude and +amplitude
/// along the unit axis, peak speed 2π amplitude / period, at rest at the reversals.
struct OscillatingTranslation {
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();  // unit
  double amplitude = 0;                             // m
  double period = 1;                                // s
  double phase = 0;                                 // rad

  Eigen::Vector3d offset(double t) const {
    return amplitude * std::sin(2 * M_PI * t / period + phase) * axis;
  }
};

}  // namespace rpvio
