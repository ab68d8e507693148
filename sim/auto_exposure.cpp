#include "sim/auto_exposure.h"

#include <algorithm>
#include <cmath>

namespace rpvio::sim {

double nextGain(const AutoExposureParams& p, double gain, double metered, double frame_period) {
  const double alpha = 1 - std::exp(-frame_period / p.time_constant);
  const double log_gain =
      std::log(gain) + alpha * (std::log(p.target) - std::log(std::max(metered, 1.0)));
  return std::clamp(std::exp(log_gain), p.min_gain, p.max_gain);
}

PinholeCamera meteringCamera(const PinholeCamera& camera) {
  constexpr int kScale = 20;
  PinholeCamera m;
  m.width = std::max(1, camera.width / kScale);
  m.height = std::max(1, camera.height / kScale);
  const double sx = static_cast<double>(m.width) / camera.width,
               sy = static_cast<double>(m.height) / camera.height;
  m.fx = camera.fx * sx;
  m.fy = camera.fy * sy;
  m.cx = (camera.cx + 0.5) * sx - 0.5;  // pixel-centre convention
  m.cy = (camera.cy + 0.5) * sy - 0.5;
  return m;
}

double meteredBrightness(const cv::Mat& radiance, const PinholeCamera& cam, double vignetting,
                         double gain) {
  const double r_max2 = cam.cx * cam.cx + cam.cy * cam.cy;
  double sum = 0;
  for (int r = 0; r < radiance.rows; ++r)
    for (int c = 0; c < radiance.cols; ++c) {
      const double d2 = (c - cam.cx) * (c - cam.cx) + (r - cam.cy) * (r - cam.cy);
      const double v = gain * (1.0 - vignetting * d2 / r_max2) * radiance.at<float>(r, c);
      sum += std::min(v, 255.0);
    }
  return sum / radiance.total();
}

AutoExposure::AutoExposure(const AutoExposureParams& params, double frame_rate)
    : params_(params), rate_(frame_rate) {}

double AutoExposure::gain(double t, const Meter& meter) {
  const auto n = static_cast<size_t>(std::max(0.0, std::floor(t * rate_ + 1e-6)));
  double phase = t - n / rate_;
  if (std::abs(phase) < 1e-6) phase = 0;  // frame times k / rate
  if (gains_.empty() || phase != phase_) gains_ = {params_.initial_gain}, phase_ = phase;
  while (gains_.size() <= n) {
    const size_t j = gains_.size() - 1;
    const double metered = meter(phase_ + j / rate_, gains_[j]);
    gains_.push_back(nextGain(params_, gains_[j], metered, 1 / rate_));
  }
  return gains_[n];
}

}  // namespace rpvio::sim
