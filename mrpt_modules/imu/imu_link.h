#pragma once
// The IMU between two frames of the window: what is wrong with its samples (a gap, a saturated
// sensor), their preintegration with the noise that follows from that, and the state it predicts
// for the later frame.
#include <memory>
#include <vector>

#include "common/sensor_types.h"
#include "mrpt_modules/imu/imu_preintegration.h"

namespace rpvio {

struct ImuLinkOptions {
  // A step between samples longer than this (s) is a gap: the interval's white-noise densities
  // are inflated by gap_noise_inflation (the held sample is a guess) ...
  double max_step_s = 0.05;
  double gap_noise_inflation = 30;
  // ... as is a saturated sensor's: an axis repeating the same value, at least this large, on
  // three consecutive samples (m/s², rad/s).
  double min_saturated_accel = 11.8;
  double min_saturated_gyro = 0.1;
};

struct ImuDefects {
  bool gap = false;  // no sample, or a step longer than max_step_s
  bool accel_saturated = false, gyro_saturated = false;
  bool any() const { return gap || accel_saturated || gyro_saturated; }
};

class ImuLink {
 public:
  /// `noise`: the noise of the preintegrations unless one is given; gravity magnitude (m/s²).
  ImuLink(const ImuNoise& noise, double gravity, const ImuLinkOptions& options)
      : noise_(noise), gravity_(gravity), options_(options) {}

  /// What is wrong with samples covering [t0, t1], if anything.
  ImuDefects defects(const std::vector<ImuSample>& samples, double t0, double t1) const;
  /// From t0 to t1 (the first sample at or before t0, interpolated at t0; the last held to t1),
  /// linearized at the biases of `speed_bias` [v, ba, bg]; nullptr without samples or time.
  std::shared_ptr<ImuPreintegration> preintegrate(const std::vector<ImuSample>& samples, double t0,
                                                  double t1, const double* speed_bias,
                                                  const ImuNoise* noise = nullptr) const;
  /// The pose [p, q] and speed_bias at the end of `pre` from those at its start (biases held):
  /// p' = p + v T + g T²/2 + q Δp, q' = q Δq, v' = v + g T + q Δv (VINS-Mono eq. 5).
  void predict(const double* pose, const double* speed_bias, const ImuPreintegration& pre,
               double* predicted_pose, double* predicted_speed_bias) const;

 private:
  ImuNoise noise_;
  double gravity_;
  ImuLinkOptions options_;
};

/// Appends samples, skipping those not after the last one already there.
void appendSamples(std::vector<ImuSample>& to, const std::vector<ImuSample>& from);

}  // namespace rpvio
