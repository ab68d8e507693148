#include "mrpt_modules/imu/gravity_direction.h"

#include <cmath>

#include "mrpt_modules/imu/so3.h"

namespace rpvio {

void GravityDirection::add(const ImuSample& s) {
  const double dt = last_ ? s.t - last_->t : 0;
  const double f = s.accel.norm();
  const bool usable = std::abs(f - g_) < 0.2 * g_;
  if (down_ && dt > 0) {
    // A world-fixed vector in the turning body: g_b(t + δt) = Exp(ω δt)ᵀ g_b(t), ω the midpoint
    // rate.
    const Eigen::Vector3d w = 0.5 * (s.gyro + last_->gyro);
    down_ = expQuaternion(w * dt).inverse() * *down_;
    if (usable) down_ = (*down_ + std::min(dt / tau_, 1.0) * (-s.accel / f - *down_)).normalized();
  } else if (!down_ && usable) {
    down_ = -s.accel / f;
  }
  last_ = s;
}

}  // namespace rpvio
