#include "sim/skeleton.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace rpvio::sim {
namespace {

Eigen::Vector3d local(const Eigen::Matrix3d& R, double x, double y, double z) {
  return Eigen::Vector3d(R * Eigen::Vector3d(x, y, z));
}

Eigen::Matrix3d yaw(double angle) {
  return Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

}  // namespace

Skeleton danceSkeleton(const Eigen::Vector2d& base, double phase, double scale, double t,
                       double shoulder_half_width) {
  Skeleton k;
  const double w = 2 * M_PI / 1.6, s = scale;  // one dance cycle every 1.6 s
  const double c = w * t + phase;
  const double sway = 0.12 * s * std::sin(c);     // hips left-right
  const double bob = 0.06 * s * std::sin(2 * c);  // up-down, twice per cycle
  const double twist = 0.35 * std::sin(c);        // torso twist
  k.scale = s;
  k.heading = yaw(0.35 * t + phase);  // slow turn in place
  k.torso = k.heading * yaw(twist) *
            Eigen::AngleAxisd(0.15 * std::sin(c), Eigen::Vector3d::UnitX()).toRotationMatrix();
  k.root = Eigen::Vector3d(base.x(), base.y(), 0);
  k.hip = k.root + local(k.heading, 0, sway, (0.95 * s) - 0.05 * s + bob);
  k.neck = k.hip + local(k.torso, 0, 0, 0.5 * s);
  k.head = k.neck + local(k.torso, 0, 0, 0.2 * s);
  for (int side = 0; side < 2; ++side) {
    const double sg = side == 0 ? 1.0 : -1.0;
    // Arms: swing up overhead and down, in opposition.
    const double lift = 1.2 + 1.1 * std::sin(c + side * M_PI);
    k.shoulder[side] = k.neck + local(k.torso, 0, sg * shoulder_half_width * s, -0.04 * s);
    k.elbow[side] =
        k.shoulder[side] + local(k.torso, 0.1 * s * std::cos(c), sg * 0.29 * s * std::sin(lift),
                                 -0.29 * s * std::cos(lift));
    const double bend = 0.6 + 0.5 * std::sin(2 * c + side);
    k.hand[side] = k.elbow[side] + local(k.torso, 0.15 * s * std::sin(bend),
                                         sg * 0.2 * s * std::sin(lift + bend),
                                         -0.26 * s * std::cos(lift + bend));
    // Legs: knees bend with the bob, feet stay planted apart.
    k.hip_joint[side] = k.hip + local(k.heading, 0, sg * 0.1 * s, 0);
    k.foot[side] = k.root + local(k.heading, 0, sg * 0.18 * s, 0.06 * s);
    const Eigen::Vector3d mid = 0.5 * (k.hip_joint[side] + k.foot[side]);
    const double leg = 0.47 * s, half = 0.5 * (k.hip_joint[side] - k.foot[side]).norm();
    const double out = std::sqrt(std::max(0.0, leg * leg - half * half));
    k.knee[side] = mid + local(k.heading, out, sg * 0.03 * s, 0);
  }
  return k;
}

Skeleton walkSkeleton(const Eigen::Vector2d& position, double heading, double gait_phase,
                      double scale) {
  Skeleton k;
  const double s = scale, g = gait_phase;
  k.scale = s;
  k.heading = yaw(heading);
  k.torso = k.heading * yaw(0.12 * std::sin(g));  // shoulders counter-rotate the hips
  k.root = Eigen::Vector3d(position.x(), position.y(), 0);
  k.hip =
      k.root + local(k.heading, 0, 0.03 * s * std::sin(g), 0.92 * s + 0.03 * s * std::cos(2 * g));
  k.neck = k.hip + local(k.torso, 0, 0, 0.5 * s);
  k.head = k.neck + local(k.torso, 0, 0, 0.2 * s);
  for (int side = 0; side < 2; ++side) {
    const double sg = side == 0 ? 1.0 : -1.0, leg_phase = g + side * M_PI;
    // Legs swing ±0.45 rad; the knee bends during the swing forward.
    const double thigh = 0.45 * std::sin(leg_phase);
    const double shin = thigh - 0.7 * std::max(0.0, std::cos(leg_phase));
    k.hip_joint[side] = k.hip + local(k.heading, 0, sg * 0.1 * s, 0);
    k.knee[side] = k.hip_joint[side] +
                   local(k.heading, 0.47 * s * std::sin(thigh), 0, -0.47 * s * std::cos(thigh));
    k.foot[side] =
        k.knee[side] + local(k.heading, 0.47 * s * std::sin(shin), 0, -0.47 * s * std::cos(shin));
    // Arms swing against the legs, forearms slightly forward.
    const double arm = -0.4 * std::sin(leg_phase), forearm = arm + 0.35;
    k.shoulder[side] = k.neck + local(k.torso, 0, sg * 0.27 * s, -0.06 * s);
    k.elbow[side] =
        k.shoulder[side] + local(k.torso, 0.29 * s * std::sin(arm), 0, -0.29 * s * std::cos(arm));
    k.hand[side] = k.elbow[side] +
                   local(k.torso, 0.26 * s * std::sin(forearm), 0, -0.26 * s * std::cos(forearm));
  }
  return k;
}

std::vector<Capsule> thinBody(const Skeleton& k) {
  const double s = k.scale;
  std::vector<Capsule> parts(10);
  parts[0] = {k.head, k.head + local(k.torso, 0, 0, 0.02 * s), 0.11 * s};
  parts[1] = {k.hip + local(k.torso, 0, 0, 0.12 * s), k.neck - local(k.torso, 0, 0, 0.05 * s),
              0.16 * s};
  for (int side = 0; side < 2; ++side) {
    parts[2 + side] = {k.shoulder[side], k.elbow[side], 0.055 * s};
    parts[4 + side] = {k.elbow[side], k.hand[side], 0.048 * s};
    parts[6 + side] = {k.hip_joint[side], k.knee[side], 0.075 * s};
    parts[8 + side] = {k.knee[side], k.foot[side], 0.06 * s};
  }
  return parts;
}

std::vector<Capsule> humanBody(const Skeleton& k) {
  const double s = k.scale;
  std::vector<Capsule> parts;
  parts.push_back({k.head, k.head + local(k.torso, 0, 0, 0.04 * s), 0.105 * s});
  for (const double sg : {1.0, -1.0})  // two columns: 2 (0.11 + 0.12) = 0.46 m wide, 0.24 m deep
    parts.push_back({k.hip + local(k.torso, 0, sg * 0.11 * s, 0.12 * s),
                     k.neck + local(k.torso, 0, sg * 0.11 * s, -0.1 * s), 0.12 * s});
  parts.push_back({k.hip_joint[0], k.hip_joint[1], 0.12 * s});  // pelvis
  for (int side = 0; side < 2; ++side) {
    parts.push_back({k.shoulder[side], k.elbow[side], 0.06 * s});
    parts.push_back({k.elbow[side], k.hand[side], 0.05 * s});
    parts.push_back({k.hip_joint[side], k.knee[side], 0.09 * s});
    parts.push_back({k.knee[side], k.foot[side], 0.065 * s});
  }
  return parts;
}

}  // namespace rpvio::sim
