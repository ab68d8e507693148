#pragma once
// Tracks on the ground that follow its homography (ground_alignment.h) instead of a corner: points
// of the region below the horizon, carried from each image to the next by the ground's aligned
// homography, published as features of the plane kGroundLabel. The estimator then treats them as
// any plane's features (reprojection and homography factors, the plane in the map, the camera
// height of calib.ini [ground] over it). Where the alignment fails (no ground in view, a blank
// image, no rotation from the gyroscope) the tracks end, and start again at the next success.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "common/options.h"
#include "mrpt_modules/core/feature_frame.h"
#include "mrpt_modules/frontend/ground_alignment.h"
#include "planes_map/plane.h"

namespace rpvio {

struct GroundTrackOptions {
  int features = 16;       // tracks kept on the ground
  double spacing_px = 60;  // at least this far apart when they start
  int max_length = 4;      // frames a track lives at most (each step adds the alignment's error)
};

class GroundTracks {
 public:
  GroundTracks(const CameraIntrinsics& camera, const GroundTrackOptions& options,
               const GroundAlignmentOptions& alignment);

  /// The ground's tracks in `image` (CV_8UC1). `R_cur_prev`: the camera's rotation since the
  /// previous image (the gyroscope's); `down`: the direction of gravity in this camera, when
  /// known. New tracks take their ids from `next_id` (shared with the corner tracks).
  std::vector<TrackedFeature> track(double t, const cv::Mat& image,
                                    const Eigen::Matrix3d* R_cur_prev, const Eigen::Vector3d* down,
                                    int& next_id);
  /// The last image pair's alignment (none on the first image or without rotation).
  const std::optional<GroundAligner::Result>& lastAlignment() const { return last_; }

  struct Point {
    int id;
    Eigen::Vector2d pixel, normalized;
    int length;  // images it was seen in
  };

 private:
  bool belowHorizon(const Eigen::Vector2d& normalized, const Eigen::Vector3d& down,
                    double margin_deg) const;
  void spawn(const cv::Size& size, const Eigen::Vector3d& down, int& next_id);

  CameraIntrinsics camera_;
  GroundTrackOptions options_;
  GroundAlignmentOptions alignment_options_;
  GroundAligner aligner_;
  GreyPyramid previous_;
  double previous_t_ = 0;
  std::optional<Eigen::Vector3d> previous_down_;  // gravity in the previous camera
  std::optional<GroundMotion> motion_;            // the last successful alignment's
  std::optional<GroundAligner::Result> last_;
  std::vector<Point> points_;
};

}  // namespace rpvio
