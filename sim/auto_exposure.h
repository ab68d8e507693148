#pragma once
// Auto-exposure: a camera's gain loop. The gain of frame k comes from the brightness metered on
// frame k−1 (a low-resolution, noise-free look at that frame's radiance with its own gain), so the
// image follows a change of brightness over a few frames, and saturates meanwhile.
// Deterministic: the gain at time t is a pure function of t (the loop replayed from the first
// frame, memoized), whatever frames were rendered before in the process and in which order.
#include <functional>
#include <vector>

#include <opencv2/core.hpp>

#include "sim/renderer.h"

namespace rpvio::sim {

struct AutoExposureParams {
  bool enabled = false;
  double target = 110;          // grey level the loop brings the image mean to
  double time_constant = 0.25;  // s
  double initial_gain = 1.0;    // of the first frame
  double min_gain = 0.125, max_gain = 8.0;

  template <class Visitor>
  void fields(Visitor& v) {
    RPVIO_OPTION(v, enabled);
    RPVIO_OPTION(v, target);
    RPVIO_OPTION(v, time_constant);
    RPVIO_OPTION(v, initial_gain);
    RPVIO_OPTION(v, min_gain);
    RPVIO_OPTION(v, max_gain);
  }
  void validate(const OptionsLoader& loader) const {
    loader.require(target > 0, "target", "must be positive");
    loader.require(time_constant > 0, "time_constant", "must be positive");
    loader.require(initial_gain > 0, "initial_gain", "must be positive");
    loader.require(min_gain > 0, "min_gain", "must be positive");
    loader.require(max_gain >= min_gain, "max_gain", "must not be below min_gain");
  }
};

/// One loop step, first order in log gain (error e^{−t/τ}):
/// log g_{k+1} = log g_k + (1 − e^{−Δ/τ}) (log target − log metered_k), clamped to the limits.
double nextGain(const AutoExposureParams& params, double gain, double metered, double frame_period);

/// The meter's view: the same field of view at 1/20 of the resolution.
PinholeCamera meteringCamera(const PinholeCamera& camera);

/// Mean grey level of the 8-bit image that `gain` makes of a radiance seen by `camera`:
/// mean of min(255, gain × vignetting × radiance).
double meteredBrightness(const cv::Mat& radiance, const PinholeCamera& camera, double vignetting,
                         double gain);

class AutoExposure {
 public:
  /// `meter(t, gain)`: the brightness metered on the frame at time t taken with that gain.
  using Meter = std::function<double(double t, double gain)>;
  AutoExposure(const AutoExposureParams& params, double frame_rate);

  /// Gain of the frame at time t: the loop run from initial_gain over the frames t − jΔ ≥ 0.
  double gain(double t, const Meter& meter);

 private:
  AutoExposureParams params_;
  double rate_;                // Hz, frames at phase_ + j / rate_
  double phase_ = 0;           // time of the chain's first frame, in [0, 1 / rate_)
  std::vector<double> gains_;  // gains_[j]: gain of the frame at phase_ + j / rate_
};

}  // namespace rpvio::sim
