#pragma once
// The direction of gravity in the body frame from the IMU alone, before (and without) any
// estimator: a complementary filter. The gyroscope turns the direction with the body,
//   ġ_b = −ω × g_b,
// and each accelerometer sample pulls it towards −f/|f| (f the specific force, which at rest or
// at constant velocity is −g) with the weight δt/τ, when |f| is within 20 % of g (a car's turns
// and accelerations bias it by their share over τ). For the front-end's horizon (ground_tracks.h).
#include <Eigen/Core>
#include <optional>

#include "common/sensor_types.h"

namespace rpvio {

class GravityDirection {
 public:
  GravityDirection(double gravity, double time_constant_s) : g_(gravity), tau_(time_constant_s) {}
  /// The next sample, in time order.
  void add(const ImuSample& sample);
  /// An estimator's gravity in the body frame (unit), which replaces the filter's: the
  /// accelerometer cannot tell a car's acceleration from a tilt, a window of IMU factors can.
  void set(const Eigen::Vector3d& down) { down_ = down.normalized(); }
  /// Unit vector along gravity in the body frame; none before the first usable sample.
  const std::optional<Eigen::Vector3d>& down() const { return down_; }

 private:
  double g_, tau_;
  std::optional<Eigen::Vector3d> down_;
  std::optional<ImuSample> last_;
};

}  // namespace rpvio
