#pragma once
// Plane-masked KLT feature tracking with per-plane homography RANSAC (RP-VIO's front-end,
// DESIGN.md §1 step 1). Pure image processing, no rawlog or module dependency: tests and the
// initializer use it directly; FeatureTrackerModule wraps it for the pipeline.
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "mrpt_modules/core/feature_frame.h"
#include "mrpt_modules/frontend/outlier_rejection.h"
#include "rawlog_io/calibration.h"
#include "rawlog_io/ini_file.h"

namespace rpvio {

struct TrackerOptions {
  bool use_masks = true;   // false: vins-mono mode (whole image, fundamental-matrix RANSAC)
  int erosion_kernel = 3;  // per-plane mask erosion (square kernel side, px)
  int erosion_iterations = 2;
  int max_features = 150;
  double min_distance = 30;  // px between features
  int klt_window = 21;
  int klt_levels = 3;  // pyramid levels above the base image
  double max_forward_backward_px = 0.5;
  bool clahe = false;
  RansacOptions ransac;  // 1 px at the virtual focal length 460

  /// Reads the keys present in `section` (others keep their defaults).
  static TrackerOptions load(const IniFile& ini, const std::string& section);
};

class FeatureTracker {
 public:
  FeatureTracker(const CameraIntrinsics& camera, const TrackerOptions& options);

  /// Tracks into a new image (CV_8UC1). `mask`: plane labels of the same instant (CV_8UC1, same
  /// size; 0 = not a static plane, 255 = unknown), ignored without use_masks. A missing or
  /// wrong-size mask, an all-zero mask or a blank image yield no features and one log line.
  FeatureFrame track(double t, const cv::Mat& image, const cv::Mat& mask);

  /// Messages about degraded input since the last call (each distinct message once).
  std::vector<std::string> takeWarnings();
  const TrackerOptions& options() const { return options_; }

 private:
  struct Track {
    int id, plane_id, length;
    cv::Point2f pixel, normalized;
  };
  void warnOnce(const std::string& message);
  std::vector<Track> propagate(const cv::Mat& image, const cv::Mat& mask);
  void rejectOutliers(std::vector<Track>& tracks) const;
  cv::Mat detectionMask(const cv::Mat& mask, const std::vector<Track>& kept) const;
  FeatureFrame publish(double t, double dt);

  CameraIntrinsics camera_;
  TrackerOptions options_;
  cv::Mat previous_image_;
  std::vector<Track> tracks_;    // current frame
  std::vector<Track> previous_;  // previous frame (same ids where tracked)
  double previous_t_ = 0;
  int next_id_ = 0;
  std::vector<std::string> warnings_, warned_;
};

/// Mean displacement (px at `virtual_focal`) of the features common to two frames; 0 when none.
double averageParallax(const FeatureFrame& a, const FeatureFrame& b, double virtual_focal = 460);
/// Number of features common to two frames.
size_t commonFeatures(const FeatureFrame& a, const FeatureFrame& b);

}  // namespace rpvio
