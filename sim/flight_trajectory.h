#pragma once
// The analytic flight of the paper's warehouse sequences (Ram et al. 2021, §V-A): a circle of
// radius R around the world origin flown counter-clockwise, a sine wave in height, a vertical
// push at the start, yaw always towards the circle's centre, and small roll/pitch oscillations.
// Closed-form derivatives, so the simulated IMU is exact.
//
// Other platforms (the motion profiles of SimConfig::profile) change the path (a road with a 90°
// turn), where the body looks (along the path), and add square-ish speed changes and head turns
// (a Fourier series of a square wave, so every derivative stays closed-form) and a walking bob.
//
// Body frame (= IMU frame): x forward, y left, z up. World: z up, origin at the circle's centre.
#include <Eigen/Geometry>

#include "common/options.h"

namespace rpvio::sim {

enum class PathShape { Circle, Road };
inline const OptionNames<PathShape> kPathShapeNames = {{"circle", PathShape::Circle},
                                                       {"road", PathShape::Road}};
enum class LookDirection { Centre, Forward };
inline const OptionNames<LookDirection> kLookDirectionNames = {{"centre", LookDirection::Centre},
                                                               {"forward", LookDirection::Forward}};

struct FlightParams {
  double radius = 15.0;                // m
  double speed = 2.5;                  // m/s, horizontal cruise speed along the circle
  double speed_ramp = 1.5;             // s, time constant of the start from rest
  double height = 2.5;                 // m, mean height above the floor
  double height_amplitude = 1.0;       // m, wave in height (starts at its lowest point)
  double height_period = 10.0;         // s
  double start_push = 0.8;             // m, extra height gained by the initial vertical push
  double start_push_time = 1.0;        // s, its time constant (peak acceleration 2 push / time^2)
  double tilt_amplitude = 0.03;        // rad, roll and pitch oscillation
  double start_angle = 0.0;            // rad, azimuth of the start on the circle
  PathShape path = PathShape::Circle;  // road: along +x from (road_start, road_start), a 90° left
                                       // turn after turn_after m over turn_length m, then +y
  double road_start = -150;            // m
  double turn_after = 200;             // m
  double turn_length = 80;             // m
  LookDirection look = LookDirection::Centre;  // of the circle (road: forward), or along the path
  double speed_swing = 0;          // m/s, the speed swings between speed ± this, square-ish
  double speed_swing_period = 20;  // s
  double yaw_swing = 0;            // rad, head turns: the yaw swings by ± this, square-ish
  double yaw_swing_period = 10;    // s
  double bob_amplitude = 0;        // m, walking bob in height
  double bob_frequency = 1.8;      // Hz

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
    RPVIO_OPTION_CHOICE(v, path, kPathShapeNames);
    RPVIO_OPTION(v, road_start);
    RPVIO_OPTION(v, turn_after);
    RPVIO_OPTION(v, turn_length);
    RPVIO_OPTION_CHOICE(v, look, kLookDirectionNames);
    RPVIO_OPTION(v, speed_swing);
    RPVIO_OPTION(v, speed_swing_period);
    RPVIO_OPTION(v, yaw_swing);
    RPVIO_OPTION(v, yaw_swing_period);
    RPVIO_OPTION(v, bob_amplitude);
    RPVIO_OPTION(v, bob_frequency);
  }
  void validate(const OptionsLoader& loader) const {
    loader.require(radius > 0, "radius", "must be positive");
    loader.require(speed_ramp > 0, "speed_ramp", "must be positive");
    loader.require(turn_length > 0, "turn_length", "must be positive");
    loader.require(speed_swing_period > 0, "speed_swing_period", "must be positive");
    loader.require(yaw_swing_period > 0, "yaw_swing_period", "must be positive");
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
