#pragma once
// Where a walking person is over a whole sequence: floor position, heading and distance walked,
// sampled at a fixed step from any path function and interpolated, plus whether the person is on
// stage (a person off stage is nowhere: not drawn, not in the way).
#include <Eigen/Core>
#include <functional>
#include <vector>

namespace rpvio::sim {

struct WalkState {
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  // floor, world
  double heading = 0;                                  // rad, direction of walking
  double distance = 0;                                 // m walked since the start
  bool on_stage = false;
};

class WalkPath {
 public:
  WalkPath() = default;
  /// Samples `position(t)` and `on_stage(t)` every `step` s over [0, duration].
  WalkPath(const std::function<Eigen::Vector2d(double)>& position,
           const std::function<bool(double)>& on_stage, double duration, double step = 0.01);
  /// Linear interpolation between samples (clamped to the sampled span).
  WalkState at(double t) const;

 private:
  std::vector<WalkState> samples_;
  double step_ = 0.01;
};

}  // namespace rpvio::sim
