#include "sim/walk_path.h"

#include <algorithm>
#include <cmath>

namespace rpvio::sim {
namespace {

double wrapAngle(double a) { return std::atan2(std::sin(a), std::cos(a)); }

}  // namespace

WalkPath::WalkPath(const std::function<Eigen::Vector2d(double)>& position,
                   const std::function<bool(double)>& on_stage, double duration, double step)
    : step_(step) {
  const auto n = static_cast<size_t>(std::ceil(duration / step)) + 2;
  samples_.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * step;
    WalkState& s = samples_[i];
    s.position = position(t);
    s.on_stage = on_stage(t);
    if (i == 0) continue;
    const WalkState& previous = samples_[i - 1];
    s.distance = previous.distance;
    s.heading = previous.heading;
    if (!s.on_stage || !previous.on_stage) continue;  // no walking across an exit or an entrance
    const Eigen::Vector2d moved = s.position - previous.position;
    s.distance += moved.norm();
    // Heading follows the velocity; standing still (< 2 cm/s) keeps the previous heading.
    if (moved.norm() > 0.02 * step) s.heading = std::atan2(moved.y(), moved.x());
  }
  // An entrance takes the heading of the first step on stage.
  for (size_t i = 0; i + 1 < n; ++i) {
    const bool entrance = samples_[i].on_stage && (i == 0 || !samples_[i - 1].on_stage);
    if (entrance && samples_[i + 1].on_stage) samples_[i].heading = samples_[i + 1].heading;
  }
}

WalkState WalkPath::at(double t) const {
  if (samples_.empty()) return {};
  const double x = std::clamp(t / step_, 0.0, static_cast<double>(samples_.size() - 1));
  const auto i = std::min(static_cast<size_t>(x), samples_.size() - 2);
  const double f = x - static_cast<double>(i);
  const WalkState &a = samples_[i], &b = samples_[i + 1];
  if (a.on_stage != b.on_stage) return a.on_stage ? a : b;  // no blending with off stage
  WalkState s;
  s.position = (1 - f) * a.position + f * b.position;
  s.heading = a.heading + f * wrapAngle(b.heading - a.heading);
  s.distance = (1 - f) * a.distance + f * b.distance;
  s.on_stage = a.on_stage;
  return s;
}

}  // namespace rpvio::sim
