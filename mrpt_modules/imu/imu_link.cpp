#include "mrpt_modules/imu/imu_link.h"

#include <algorithm>
#include <cmath>

namespace rpvio {

void appendSamples(std::vector<ImuSample>& to, const std::vector<ImuSample>& from) {
  for (const auto& s : from)
    if (to.empty() || s.t > to.back().t) to.push_back(s);
}

ImuDefects ImuLink::defects(const std::vector<ImuSample>& samples, double t0, double t1) const {
  ImuDefects d;
  d.gap = samples.empty();
  if (d.gap) return d;
  double longest_step = t1 - samples.back().t;
  for (size_t k = 1; k < samples.size(); ++k)
    longest_step = std::max(longest_step, samples[k].t - std::max(t0, samples[k - 1].t));
  d.gap = longest_step > options_.max_step_s;
  // A saturated axis repeats its limit exactly; noise never repeats a value three times.
  auto stuck = [&](size_t k, const Eigen::Vector3d ImuSample::*sensor, int axis, double floor) {
    const double v = (samples[k].*sensor)[axis];
    return std::abs(v) >= floor && v == (samples[k - 1].*sensor)[axis] &&
           v == (samples[k - 2].*sensor)[axis];
  };
  for (size_t k = 2; k < samples.size(); ++k)
    for (int axis = 0; axis < 3; ++axis) {
      d.accel_saturated |= stuck(k, &ImuSample::accel, axis, options_.min_saturated_accel);
      d.gyro_saturated |= stuck(k, &ImuSample::gyro, axis, options_.min_saturated_gyro);
    }
  return d;
}

std::shared_ptr<ImuPreintegration> ImuLink::preintegrate(const std::vector<ImuSample>& samples,
                                                         double t0, double t1,
                                                         const double* speed_bias,
                                                         const ImuNoise* noise) const {
  if (samples.empty() || t1 <= t0) return nullptr;
  // Samples held constant over their interval; the first one is interpolated at t0 when the next
  // sample lies after t0, the last one extended to t1.
  ImuSample first = samples.front();
  if (samples.size() > 1 && first.t < t0 && samples[1].t > t0) {
    const double a = (t0 - first.t) / (samples[1].t - first.t);
    first.accel = (1 - a) * first.accel + a * samples[1].accel;
    first.gyro = (1 - a) * first.gyro + a * samples[1].gyro;
  }
  // An IMU gap (samples missing, the last one held over it) or a saturated sensor: the values are
  // guesses, so the factor's noise is inflated (the sensor's, both over a gap) and the cameras
  // carry the motion.
  ImuNoise n = noise ? *noise : noise_;
  const ImuDefects d = defects(samples, t0, t1);
  if (d.gap || d.accel_saturated) n.accel_noise_density *= options_.gap_noise_inflation;
  if (d.gap || d.gyro_saturated) n.gyro_noise_density *= options_.gap_noise_inflation;
  auto pre = std::make_shared<ImuPreintegration>(
      first.accel, first.gyro, Eigen::Vector3d(speed_bias + 3), Eigen::Vector3d(speed_bias + 6), n);
  double t = t0;
  for (size_t k = 1; k < samples.size(); ++k) {
    if (samples[k].t <= t) continue;
    pre->push(samples[k].t - t, samples[k].accel, samples[k].gyro);
    t = samples[k].t;
  }
  if (t1 > t) pre->push(t1 - t, samples.back().accel, samples.back().gyro);
  return pre;
}

void ImuLink::predict(const double* pose, const double* speed_bias, const ImuPreintegration& pre,
                      double* predicted_pose, double* predicted_speed_bias) const {
  const Eigen::Vector3d g(0, 0, -gravity_);
  const double T = pre.sumDt();
  const Eigen::Quaterniond q(pose[6], pose[3], pose[4], pose[5]);
  const Eigen::Vector3d v(speed_bias);
  const Eigen::Vector3d p =
      Eigen::Vector3d(pose[0], pose[1], pose[2]) + v * T + 0.5 * g * T * T + q * pre.deltaP();
  const Eigen::Quaterniond q_new = (q * pre.deltaQ()).normalized();
  const Eigen::Vector3d v_new = v + g * T + q * pre.deltaV();
  const double out[7] = {p.x(), p.y(), p.z(), q_new.x(), q_new.y(), q_new.z(), q_new.w()};
  std::copy(out, out + 7, predicted_pose);
  for (int i = 0; i < 3; ++i) predicted_speed_bias[i] = v_new[i];
  std::copy(speed_bias + 3, speed_bias + 9, predicted_speed_bias + 3);
}

}  // namespace rpvio
