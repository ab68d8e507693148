#pragma once
// What the front-end publishes per image and the initializer/estimator consume.
#include <Eigen/Core>
#include <vector>

namespace rpvio {

struct TrackedFeature {
  int id = -1;                                      // stable over the track's life
  int plane_id = 0;                                 // mask label; 0 = no plane (vins-mono mode)
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();  // distorted image coordinates (px)
  Eigen::Vector2d normalized = Eigen::Vector2d::Zero();  // undistorted, z = 1 plane
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();    // normalized coordinates per second
  int track_length = 1;                                  // frames this feature has been tracked
};

struct FeatureFrame {
  double t = 0;        // image timestamp (s), camera clock; the estimator moves it to the IMU clock
  double image_t = 0;  // the image's timestamp as the rawlog has it, never moved
  std::vector<TrackedFeature> features;
};

/// Mean displacement (px at `virtual_focal`) of the features common to two frames; 0 when none.
double averageParallax(const FeatureFrame& a, const FeatureFrame& b, double virtual_focal = 460);
/// Number of features common to two frames.
size_t commonFeatures(const FeatureFrame& a, const FeatureFrame& b);

}  // namespace rpvio
