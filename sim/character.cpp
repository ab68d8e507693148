#include "sim/character.h"

#include <cmath>

#include "sim/skeleton.h"

namespace rpvio::sim {
namespace {

constexpr double kStrideLength = 1.5;       // m walked per gait cycle (two steps) at 1.8 m height
constexpr double kClothesCellHuman = 0.05;  // m, the clothes pattern's cell (crate-like corners)

}  // namespace

Character Character::paperDancer(const Eigen::Vector2d& base, double phase, double height,
                                 int seed) {
  Character c;
  c.base_ = base, c.phase_ = phase, c.scale_ = height / 1.8, c.seed_ = seed;
  c.pose(0.0);
  return c;
}

Character Character::dancer(const Eigen::Vector2d& base, double phase, double height, int seed) {
  Character c = paperDancer(base, phase, height, seed);
  c.human_bulk_ = true;
  c.pose(0.0);
  return c;
}

Character Character::walker(WalkPath path, double height, int seed) {
  Character c;
  c.motion_ = Motion::Walk, c.human_bulk_ = true;
  c.path_ = std::move(path), c.scale_ = height / 1.8, c.seed_ = seed;
  c.pose(0.0);
  return c;
}

void Character::pose(double t) {
  Skeleton skeleton;
  if (motion_ == Motion::Dance) {
    skeleton = danceSkeleton(base_, phase_, scale_, t, human_bulk_ ? 0.27 : 0.2);
  } else {
    const WalkState s = path_.at(t);
    on_stage_ = s.on_stage;
    if (!on_stage_) return;
    skeleton = walkSkeleton(s.position, s.heading, 2 * M_PI * s.distance / (kStrideLength * scale_),
                            scale_);
  }
  const Eigen::Vector3d centre = skeleton.root + Eigen::Vector3d(0, 0, 1.0 * scale_);
  if (human_bulk_)
    figure_.setParts(humanBody(skeleton), centre, kClothesCellHuman, seed_);
  else
    figure_.setParts(thinBody(skeleton), centre, 0.06 * scale_, seed_);
}

std::optional<CharacterHit> Character::intersect(const Eigen::Vector3d& origin,
                                                 const Eigen::Vector3d& dir, double t_max,
                                                 uint64_t parts) const {
  if (!on_stage_) return std::nullopt;
  return figure_.intersect(origin, dir, t_max, parts);
}

double Character::signedDistance(const Eigen::Vector3d& x) const {
  return on_stage_ ? figure_.signedDistance(x) : INFINITY;
}

}  // namespace rpvio::sim
