#include "sim/crowd.h"

#include <cmath>
#include <functional>
#include <random>

namespace rpvio::sim {
namespace {

enum class Role { Crosser, Companion, Dancer };
const Role kRoles[] = {Role::Companion, Role::Crosser,   Role::Companion, Role::Crosser,
                       Role::Dancer,    Role::Companion, Role::Crosser,   Role::Companion};

/// Depths of successive crossings, as fractions of the depth range (squared below: near is
/// frequent): two close passes in every five.
const double kCrossingDepthOrder[] = {0.05, 0.5, 0.0, 0.3, 0.8};

/// Where the group's members walk across the view, as fractions of its half width.
const double kCompanionLateral[] = {0.0, -0.55, 0.55, -0.3, 0.3};

constexpr double kBodyMargin = 0.6;  // m, a person's half width plus arms: out of view beyond it
constexpr double kMaxCrossing = 12;  // s, a crossing slower than this ends off stage anyway

struct Appearance {
  double start, end;  // s, on stage in [start, end)
  std::function<Eigen::Vector2d(double)> position;
};

class CameraGround {
 public:
  CameraGround(const FlightTrajectory& flight, const Eigen::Isometry3d& T_BC, double tan_half_fov)
      : flight_(flight), T_BC_(T_BC), tan_half_fov_(tan_half_fov) {}

  GroundView at(double t) const {
    const FlightState s = flight_.at(t);
    const Eigen::Vector3d c = s.p + s.R_wb * T_BC_.translation();
    const Eigen::Vector3d z = s.R_wb * T_BC_.linear().col(2);
    GroundView v;
    v.position = c.head<2>();
    v.forward = z.head<2>().normalized();
    v.left = Eigen::Vector2d(-v.forward.y(), v.forward.x());
    return v;
  }
  /// A person at floor point p is out of the horizontal view (with a body's margin).
  bool outOfView(double t, const Eigen::Vector2d& p) const {
    const GroundView v = at(t);
    const Eigen::Vector2d d = p - v.position;
    const double ahead = d.dot(v.forward);
    return ahead < 0.3 || std::abs(d.dot(v.left)) > ahead * tan_half_fov_ + kBodyMargin;
  }
  double tanHalfFov() const { return tan_half_fov_; }

 private:
  const FlightTrajectory& flight_;
  Eigen::Isometry3d T_BC_;
  double tan_half_fov_;
};

double smoothstep(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3 - 2 * x);
}

/// Straight walks across the view, one after the other; the first starts in view at t = 0.
std::vector<Appearance> crossings(const CrowdParams& p, const CameraGround& camera, double duration,
                                  int person, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  std::vector<Appearance> out;
  double start = 0;
  for (int j = 0; start < duration; ++j) {
    const double q = kCrossingDepthOrder[(j + person) % 5] + 0.04 * (uni(rng) - 0.5);
    const double depth =
        p.crossing_depth_min + (p.crossing_depth_max - p.crossing_depth_min) * q * q;
    const GroundView v = camera.at(start);
    const double side = ((j + person) % 2 == 0) ? 1.0 : -1.0;  // walking left or right
    const double angle = 0.3 * (uni(rng) - 0.5);
    const Eigen::Vector2d velocity = p.walking_speed * (0.85 + 0.3 * uni(rng)) * side *
                                     (std::cos(angle) * v.left + std::sin(angle) * v.forward);
    // Enter on the side the person drifts in from, as seen from the moving camera.
    const Eigen::Vector2d centre = v.position + depth * v.forward;
    const GroundView later = camera.at(start + 0.2);
    const double drift = (centre + 0.2 * velocity - later.position).dot(later.left) -
                         (centre - v.position).dot(v.left);
    const double edge = depth * camera.tanHalfFov() + kBodyMargin + 0.3;
    const double lateral = (drift > 0 ? -1 : 1) * (j == 0 ? 0.3 * depth : edge);  // first: in view
    const Eigen::Vector2d p0 = centre + lateral * v.left;
    auto position = [=](double t) -> Eigen::Vector2d { return p0 + (t - start) * velocity; };
    double end = start + 0.3;
    while (end < start + kMaxCrossing && !camera.outOfView(end, position(end))) end += 0.05;
    out.push_back({start, end, position});
    start = end + 0.2 + 0.4 * uni(rng);
  }
  return out;
}

/// The group's appearances: in place ahead of the camera (depth, lateral) for companion_hold s,
/// walking in from the nearer side and out to it over 3 s; the first starts in place at t = 0.
/// In the middle half of each stay the group closes in on the camera (depth and lateral offset
/// shrink by companion_close_in), as a crowd does.
std::vector<Appearance> companionAppearances(const CrowdParams& p, const CameraGround& camera,
                                             double duration, double depth, double lateral) {
  constexpr double kWalkInOut = 3.0;
  std::vector<Appearance> out;
  double start = -kWalkInOut;
  const double side = lateral >= 0 ? 1.0 : -1.0;  // the group member's nearer edge
  for (int e = 0; start < duration; ++e) {
    const double outside = depth * camera.tanHalfFov() + kBodyMargin + 0.4;
    const double hold_start = start + kWalkInOut, hold_end = hold_start + p.companion_hold;
    auto position = [=, &camera](double t) -> Eigen::Vector2d {
      const GroundView v = camera.at(t);
      const double x = lateral +
                       (side * outside - lateral) * smoothstep((hold_start - t) / kWalkInOut) +
                       (side * outside - lateral) * smoothstep((t - hold_end) / kWalkInOut);
      const double quarter = p.companion_hold / 4;
      const double closer =
          1 - p.companion_close_in * (smoothstep((t - hold_start - quarter + 1) / 2) -
                                      smoothstep((t - hold_end + quarter + 1) / 2));
      return v.position + closer * (depth * v.forward + x * v.left);
    };
    out.push_back({std::max(0.0, start), hold_end + kWalkInOut, position});
    start = hold_end + kWalkInOut + p.companion_gap;
  }
  return out;
}

WalkPath pathOf(const std::vector<Appearance>& appearances, double duration) {
  auto find = [&appearances](double t) -> const Appearance* {
    for (const Appearance& a : appearances)
      if (t >= a.start && t < a.end) return &a;
    return nullptr;
  };
  return WalkPath(
      [&](double t) -> Eigen::Vector2d {
        const Appearance* a = find(t);
        return a ? a->position(t) : Eigen::Vector2d(1e3, 1e3);
      },
      [&](double t) { return find(t) != nullptr; }, duration);
}

}  // namespace

std::vector<Character> makeFlightCrowd(int count, const CrowdParams& p,
                                       const FlightTrajectory& flight,
                                       const Eigen::Isometry3d& T_BC, double tan_half_fov,
                                       double duration, uint64_t seed) {
  const CameraGround camera(flight, T_BC, tan_half_fov);
  std::mt19937_64 rng(seed * 7919 + 5);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  int companions = 0, dancers = 0;
  for (int k = 0; k < count; ++k) companions += kRoles[k % 8] == Role::Companion;
  std::vector<Character> crowd;
  for (int k = 0, companion = 0; k < count; ++k) {
    const double height =
        p.person_height_min + (p.person_height_max - p.person_height_min) * uni(rng);
    const int figure_seed = static_cast<int>(seed) * 13 + k;
    switch (kRoles[k % 8]) {
      case Role::Crosser:
        crowd.push_back(Character::walker(pathOf(crossings(p, camera, duration, k, rng), duration),
                                          height, figure_seed));
        break;
      case Role::Companion: {
        // The nearest in the middle of the view, the others farther and to the sides.
        const double f = companions > 1 ? companion / (companions - 1.0) : 0.0;
        const double depth =
            p.companion_depth_min + (p.companion_depth_max - p.companion_depth_min) * f;
        const double lateral = kCompanionLateral[companion % 5] * depth * tan_half_fov;
        crowd.push_back(Character::walker(
            pathOf(companionAppearances(p, camera, duration, depth, lateral), duration), height,
            figure_seed));
        ++companion;
        break;
      }
      case Role::Dancer: {
        const double radius = flight.params().radius - p.dancer_depth;
        const double angle = flight.params().start_angle + 0.35 + 2.1 * dancers++;
        crowd.push_back(
            Character::dancer(radius * Eigen::Vector2d(std::cos(angle), std::sin(angle)), 1.3 * k,
                              height, figure_seed));
        break;
      }
    }
  }
  return crowd;
}

}  // namespace rpvio::sim
