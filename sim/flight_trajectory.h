#pragma once
// The analytic flight of the paper's warehouse sequences (Ram et al. 2021, §V-A): a circle of
// radius R around the world origin flown counter-clockwise, a sine wave in height, a vertical
// push at the start, yaw always towards the circle's centre, and small roll/pitch oscillations.
// Closed-form derivatives, so the simulated IMU is exact.
//
// Body frame (= IMU frame): x forward, y left, z up. World: z up, origin at the circle's centre.
#include <Eigen/Geometry>

#include "common/options.h"

namespace rpvio::sim {

struct FlightParams {
  double radius = 15.0;           // m
  double speed = 2.5;             // m/s, horizontal cruise speed along the circle
  double speed_ramp = 1.5;        // s, time constant of the start from rest
  double height = 2.5;            // m, mean height above the floor
  double height_amplitude = 1.0;  // m, wave in height (starts at its lowest point)
  double height_period = 10.0;    // s
  double start_push = 0.8;        // m, extra height gained by the initial vertical push
  double start_push_time = 1.0;   // s, its time constant (peak acceleration 2 push / time^2)
  double tilt_amplitude = 0.03;   // rad, roll and pitch oscillation
  double start_angle = 0.0;       // rad, azimuth of the start on the circle

  template <class Visitor>
  void fields(Visitor& v) {
    RPVIO_OPTION(v, radius);
    RPVIO_OPTION(v, speed);
    RPVIO_OPTION(v, speed_ramp);
    RPVIO_OPTION(v, height);
    RPVIO_OPTION(v, height_amplitude);
    RPVIO_OPTION(v, height_period);
    RPVIO_OPTION(v, start_push);
    RPVIO_OPTION(v, start_push_time);
    RPVIO_OPTION(v, tilt_amplitude);
    RPVIO_OPTION(v, start_angle);
  }
  void validate(const OptionsLoader& loader) const {
    loader.require(radius > 0, "radius", "must be positive");
  }
};

struct FlightState {
  Eigen::Vector3d p, v, a;  // world position, velocity, acceleration
  Eigen::Matrix3d R_wb;     // body orientation in the world
  Eigen::Vector3d omega_b;  // angular rate in the body frame
};

class FlightTrajectory {
 public:
  explicit FlightTrajectory(const FlightParams& params) : params_(params) {}
  FlightState at(double t) const;
  const FlightParams& params() const { return params_; }

 private:
  FlightParams params_;
};

}  // namespace rpvio::sim
