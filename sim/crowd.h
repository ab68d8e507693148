#pragma once
// The hard profile's crowd (issue #40): people with human bulk placed around the camera's flight so
// that they fill the view — walkers crossing it at 1–8 m, a group walking with the camera for
// several seconds (dynamic features moving like the camera: what RANSAC cannot reject), and dancers
// just inside the flight circle that the camera passes closely. On stage from the first frame.
#include <Eigen/Geometry>
#include <vector>

#include "common/options.h"
#include "sim/character.h"
#include "sim/flight_trajectory.h"

namespace rpvio::sim {

enum class CrowdLayout { Ring, Flight };
inline const OptionNames<CrowdLayout> kCrowdLayoutNames = {{"ring", CrowdLayout::Ring},
                                                           {"flight", CrowdLayout::Flight}};

struct CrowdParams {
  CrowdLayout layout = CrowdLayout::Ring;  // ring: the paper's dancers; flight: this crowd
  double person_height_min = 1.6, person_height_max = 1.9;      // m
  double walking_speed = 1.4;                                   // m/s, ±15 % per crossing
  double crossing_depth_min = 1.2, crossing_depth_max = 8;      // m ahead of the camera
  double companion_depth_min = 1.2, companion_depth_max = 2.4;  // m ahead of the camera
  double companion_hold = 12;       // s the group keeps its place in the view
  double companion_close_in = 0.5;  // fraction of its distance the group closes in mid-stay
  double companion_gap = 0.5;       // s off stage between two appearances of the group
  double dancer_depth = 2;          // m inside the flight circle

  template <class Visitor>
  void fields(Visitor& v) {
    RPVIO_OPTION_CHOICE(v, layout, kCrowdLayoutNames);
    RPVIO_OPTION(v, person_height_min);
    RPVIO_OPTION(v, person_height_max);
    RPVIO_OPTION(v, walking_speed);
    RPVIO_OPTION(v, crossing_depth_min);
    RPVIO_OPTION(v, crossing_depth_max);
    RPVIO_OPTION(v, companion_depth_min);
    RPVIO_OPTION(v, companion_depth_max);
    RPVIO_OPTION(v, companion_hold);
    RPVIO_OPTION(v, companion_close_in);
    RPVIO_OPTION(v, companion_gap);
    RPVIO_OPTION(v, dancer_depth);
  }
  void validate(const OptionsLoader& loader) const {
    loader.require(crossing_depth_min > 0, "crossing_depth_min", "must be positive");
    loader.require(companion_depth_min > 0, "companion_depth_min", "must be positive");
  }
};

/// What the camera looks at, on the floor: its position, forward and left unit directions.
struct GroundView {
  Eigen::Vector2d position, forward, left;
};

/// `count` people; roles cycle companion, crosser, companion, crosser, dancer, companion, crosser,
/// companion (one person walks with the camera; eight are a group of four, three crossers and a
/// dancer).
/// `tan_half_fov`: the image's half width over the focal length (1 for 90°).
std::vector<Character> makeFlightCrowd(int count, const CrowdParams& params,
                                       const FlightTrajectory& flight,
                                       const Eigen::Isometry3d& T_BC, double tan_half_fov,
                                       double duration, uint64_t seed);

}  // namespace rpvio::sim
