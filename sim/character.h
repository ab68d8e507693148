#pragma once
// A moving person of the scene: how it moves (dancing in place, or walking a path) and its body
// (the paper suite's thin dancer, or human bulk), posed at any time as a capsule figure.
#include <optional>

#include "sim/capsule_figure.h"
#include "sim/walk_path.h"

namespace rpvio::sim {

class Character {
 public:
  /// The paper suite's dancer (thin limbs), dancing at `base`; `height` ~1.8 m.
  static Character paperDancer(const Eigen::Vector2d& base, double phase, double height, int seed);
  /// A person with human bulk dancing in place at `base`.
  static Character dancer(const Eigen::Vector2d& base, double phase, double height, int seed);
  /// A person with human bulk walking `path`.
  static Character walker(WalkPath path, double height, int seed);

  /// Poses the figure at time t (seconds); the queries below use the posed figure.
  void pose(double t);
  /// Off stage (a walker between its appearances): never hit, infinitely far.
  bool onStage() const { return on_stage_; }
  std::optional<CharacterHit> intersect(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                                        double t_max, uint64_t parts = ~0ULL) const;
  double signedDistance(const Eigen::Vector3d& x) const;
  const CapsuleFigure& figure() const { return figure_; }

 private:
  enum class Motion { Dance, Walk };
  Motion motion_ = Motion::Dance;
  bool human_bulk_ = false, on_stage_ = true;
  Eigen::Vector2d base_ = Eigen::Vector2d::Zero();
  double phase_ = 0, scale_ = 1;
  int seed_ = 0;
  WalkPath path_;
  CapsuleFigure figure_;
};

}  // namespace rpvio::sim
