#include "mrpt_modules/estimator/estimator_options.h"

namespace rpvio {

void EstimatorOptions::validate(const OptionsLoader& loader) const {
  loader.require(window_size >= 3, "window_size", "must be at least 3");
  loader.require(max_iterations >= 0, "max_iterations", "must be 0 or more");
  loader.require(plane_covariance_every >= 1, "plane_covariance_every", "must be 1 or more");
  loader.require(verify_static_px < verify_moving_px, "verify_moving_px",
                 "must be more than verify_static_px");
  loader.require(verify_reject_after >= 1, "verify_reject_after", "must be 1 or more");
  loader.require(verify_min_features >= 3, "verify_min_features", "must be 3 or more");
  loader.require(discover_min_features >= 3, "discover_min_features", "must be 3 or more");
  loader.require(discover_span_s > 0, "discover_span_s", "must be positive");
  loader.require(verify_span_s > 0, "verify_span_s", "must be positive");
  loader.require(init_fallback_parallax_px > 0 && init_fallback_parallax_px <= init_parallax_px,
                 "init_fallback_parallax_px", "must be positive and at most init_parallax_px");
  loader.require(camera_height_sigma >= 0, "camera_height_sigma", "must be 0 (off) or positive");
  loader.require(ground_pixel_sigma > 0, "ground_pixel_sigma", "must be positive");
  loader.require(accel_bias_prior_sigma >= 0, "accel_bias_prior_sigma",
                 "must be 0 (off) or positive");
  loader.require(time_offset_systematic_margin >= 0, "time_offset_systematic_margin",
                 "must be 0 (off) or positive");
  loader.require(time_offset_window_s >= 0 && time_offset_window_s <= 10, "time_offset_window_s",
                 "must be 0 to 10 s");
  loader.require(init_window_frames >= 2, "init_window_frames", "must be 2 or more");
  loader.require(discover_confirm_after >= 1, "discover_confirm_after", "must be 1 or more");
  loader.require(discover_reject_after >= 1, "discover_reject_after", "must be 1 or more");
}

ImuLinkOptions EstimatorOptions::imuLinkOptions() const {
  ImuLinkOptions o;
  o.max_step_s = max_imu_step_s;
  o.gap_noise_inflation = imu_gap_noise_inflation;
  o.min_saturated_accel = min_saturated_accel;
  o.min_saturated_gyro = min_saturated_gyro;
  return o;
}

PlaneVerifierOptions EstimatorOptions::planeVerifierOptions() const {
  PlaneVerifierOptions o;
  o.enabled = verify_planes;
  o.span_s = verify_span_s;
  o.min_parallax_px = verify_min_parallax_px;
  o.min_features = verify_min_features;
  o.static_px = verify_static_px;
  o.moving_px = verify_moving_px;
  o.moving_noise_ratio = verify_moving_noise_ratio;
  o.reject_after = verify_reject_after;
  o.focal_px = virtual_focal;
  return o;
}

PlaneDiscoveryOptions EstimatorOptions::planeDiscoveryOptions() const {
  PlaneDiscoveryOptions o;
  o.enabled = discover_planes;
  o.span_s = discover_span_s;
  o.min_parallax_px = discover_min_parallax_px;
  o.epipolar_px = discover_epipolar_px;
  o.plane_px = discover_plane_px;
  o.plane_sigmas = discover_plane_sigmas;
  o.min_features = discover_min_features;
  o.max_planes = discover_max_planes;
  o.confirm_after = discover_confirm_after;
  o.reject_after = discover_reject_after;
  o.adopt_young = discover_adopt_young;
  o.static_points = discover_static_points;
  o.focal_px = virtual_focal;
  return o;
}

InitializerOptions EstimatorOptions::initializerOptions() const {
  InitializerOptions o;
  o.method = initializer;
  o.min_window_s = init_window_s;
  o.min_parallax_px = init_parallax_px;
  o.fallback_parallax_px = init_fallback_parallax_px;
  o.max_relative_scale_sigma = init_max_scale_sigma;
  o.virtual_focal = virtual_focal;
  o.pixel_sigma = pixel_sigma;
  return o;
}

}  // namespace rpvio
