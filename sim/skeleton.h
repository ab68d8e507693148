#pragma once
// The joints of a person in one pose, and the capsule bodies built on them: the paper suite's thin
// dancer, and a person with human bulk (torso 0.4–0.5 m wide, limbs 0.1–0.2 m thick).
#include <Eigen/Core>
#include <array>
#include <vector>

#include "sim/capsule_figure.h"

namespace rpvio::sim {

struct Skeleton {
  double scale = 1;                                // height / 1.8 m
  Eigen::Vector3d root = Eigen::Vector3d::Zero();  // floor point under the hips
  Eigen::Matrix3d heading = Eigen::Matrix3d::Identity(), torso = Eigen::Matrix3d::Identity();
  Eigen::Vector3d hip, neck, head;  // columns of the frames: x forward, y left, z up
  std::array<Eigen::Vector3d, 2> shoulder, elbow, hand, hip_joint, knee, foot;  // left, right
};

/// Dancing in place at `base` (one cycle every 1.6 s, slow turn); `shoulder_half_width` in units of
/// scale (the paper's dancer: 0.2).
Skeleton danceSkeleton(const Eigen::Vector2d& base, double phase, double scale, double t,
                       double shoulder_half_width);
/// Walking: `gait_phase` (rad) advances 2π per stride (two steps); heading is the walking
/// direction.
Skeleton walkSkeleton(const Eigen::Vector2d& position, double heading, double gait_phase,
                      double scale);

/// The paper's dancer: head, torso, 2 upper arms, 2 forearms, 2 thighs, 2 shins (thin limbs).
std::vector<Capsule> thinBody(const Skeleton& s);
/// Human bulk: head, a two-column torso 0.46 m wide, pelvis, limbs 0.10–0.18 m thick (× scale).
std::vector<Capsule> humanBody(const Skeleton& s);

}  // namespace rpvio::sim
