#include "mrpt_modules/estimator/estimator_options.h"

namespace rpvio {

void EstimatorOptions::validate(const OptionsLoader& loader) const {
  loader.require(window_size >= 3, "window_size", "must be at least 3");
  loader.require(max_iterations >= 0, "max_iterations", "must be 0 or more");
}

ImuLinkOptions EstimatorOptions::imuLinkOptions() const {
  ImuLinkOptions o;
  o.max_step_s = max_imu_step_s;
  o.gap_noise_inflation = imu_gap_noise_inflation;
  o.min_saturated_accel = min_saturated_accel;
  o.min_saturated_gyro = min_saturated_gyro;
  return o;
}

InitializerOptions EstimatorOptions::initializerOptions() const {
  InitializerOptions o;
  o.method = initializer;
  o.min_window_s = init_window_s;
  o.min_parallax_px = init_parallax_px;
  o.virtual_focal = virtual_focal;
  o.pixel_sigma = pixel_sigma;
  return o;
}

}  // namespace rpvio
