#pragma once
// Plane-masked KLT feature tracking with per-plane homography RANSAC (RP-VIO's front-end,
// DESIGN.md §1 step 1). Pure image processing, no rawlog or module dependency: tests and the
// initializer use it directly; FeatureTrackerModule wraps it for the pipeline.
#include <Eigen/Core>
#include <map>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "common/options.h"
#include "common/sensor_types.h"
#include "mrpt_modules/core/feature_frame.h"
#include "mrpt_modules/frontend/corner_detector.h"
#include "mrpt_modules/frontend/ground_tracks.h"
#include "mrpt_modules/frontend/outlier_rejection.h"
#include "mrpt_modules/frontend/plane_feature_budget.h"

namespace rpvio {

struct TrackerOptions {
  bool use_masks = true;   // false: vins-mono mode (whole image, fundamental-matrix RANSAC)
  int erosion_kernel = 3;  // per-plane mask erosion (square kernel side, px)
  int erosion_iterations = 2;
  // A track is dropped (and no corner detected) where another label lies within this many pixels:
  // a KLT window straddling two surfaces follows a mix of their motions (0 = paper's behaviour).
  int window_margin = 10;
  int max_features = 150;
  double min_distance = 30;  // px between features
  // A plane whose detectable pixels could not hold this many features at min_distance gets a
  // tighter spacing (down to one KLT window: closer windows overlap and their errors correlate)
  // and its corners first (plane_feature_budget.h); the total stays max_features. 0 (or less):
  // one spacing for all (VINS-Mono's detector). Measurements:
  // docs/notes/2026-11-26-plane-feature-budget.md.
  int min_plane_features = 20;
  int klt_window = 21;  // px, side of the KLT window
  // Pyramid levels above the base image (2: three levels); 3 follows larger image motion, for fast
  // real sequences (docs/notes/2026-11-26-frontend-timing.md).
  int klt_levels = 2;
  // KLT starts each track where the gyroscope's rotation since the previous image moves it
  // (rotation_prediction.h; FeatureTrackerModule integrates the IMU's gyroscope between the
  // images), instead of at its previous pixel.
  bool predict_rotation = true;
  // With predict_rotation and masks: a plane's tracks start where its homography at constant
  // velocity moves them (its last interval's homography, turned by the gyroscope's rotations;
  // motion_prediction.h), so fast translation over a near plane (a car's road) needs no deep
  // pyramid either. Planes with fewer than 8 inliers in the last interval: the rotation alone.
  // Off by default: rpvio-multi was worse with it on the paper suite
  // (docs/notes/2026-11-29-plane-motion-prediction.md).
  bool predict_plane_motion = false;
  double max_forward_backward_px = 0.5;  // px
  // A plane absent from the whole mask (a segmentation network missed it) keeps its tracks for
  // this many frames, on their own forward-backward, anchor and per-plane RANSAC checks; 0: they
  // end with the plane's label, as every track leaving its label does.
  int missed_plane_frames = 1;
  // KLT's minimum eigenvalue (OpenCV's normalization: the smaller eigenvalue of the window's
  // gradient matrix over its pixel count, gradients in grey levels per px / 32): a track ends when
  // its full-resolution window falls below it (a single edge: the aperture problem); coarse levels
  // below it are skipped. The test is absolute, so higher values also end the tracks of surfaces
  // in shade (docs/notes/2026-11-26-klt-threshold.md).
  double klt_min_eigenvalue = 5e-3;
  bool clahe = false;
  // Outlier rejection between consecutive frames: per plane a homography (masks), else a
  // fundamental matrix, by RANSAC with this threshold (px) at the virtual focal length (px).
  double ransac_threshold_px = 1.0;
  double virtual_focal = 460.0;
  // Re-align every track on the image it was born in (frame-to-frame result as initial guess), the
  // birth patch warped by its plane's homographies, so KLT errors do not accumulate along the
  // track.
  bool anchor_refinement = true;
  double max_warp_scale = 3.0;  // a track ends when its warp stretches or shrinks more than this
  // Without masks, a track's birth patch is warped by the local affine motion of its 8 nearest
  // neighbours (within 4 min_distance) instead of not at all: surfaces seen at an angle keep
  // their tracks as the view changes (local_image_motion.h).
  bool local_warps = true;
  // Corners are detected on this pyramid level (0 = full resolution; 1 = half, 4x cheaper), or
  // with -1 on the coarsest level still kAutoDetectionWidth px wide (0 below 1280 px).
  int detection_level = -1;
  static constexpr int kAutoDetectionWidth = 640;
  // The image is cut into square cells this many px wide (0: not): after the detection over the
  // whole image, a cell holding fewer than min_cell_features tracks and corners gets corners of
  // its own, the quality threshold relative to its own strongest corner. A street's asphalt has
  // no corner within 1 % of a facade's strongest (docs/notes/2026-12-05-real-street-images.md).
  int detection_cell_px = 0;
  int min_cell_features = 4;
  // Tracks on the ground below the horizon carried by its homography, found by direct alignment
  // of the two images (ground_tracks.h), this many at a time as features of the plane
  // kGroundLabel (0: none). Needs the gyroscope's rotation and gravity's direction (the module's
  // IMU). For cars and ground robots, whose road has few corners to track.
  int ground_features = 0;
  // FeatureTrackerModule: decode and track the images on a second thread while the modules after
  // it work on earlier frames, up to frames_in_flight images ahead (the same outputs, that many
  // frames later on the bus; stats.csv's per-frame times then overlap).
  bool pipelined = false;
  int frames_in_flight = 3;

  template <class Visitor>
  void fields(Visitor& v) {
    RPVIO_OPTION(v, use_masks);
    RPVIO_OPTION(v, erosion_kernel);
    RPVIO_OPTION(v, erosion_iterations);
    RPVIO_OPTION(v, window_margin);
    RPVIO_OPTION(v, max_features);
    RPVIO_OPTION(v, min_distance);
    RPVIO_OPTION(v, min_plane_features);
    RPVIO_OPTION(v, klt_window);
    RPVIO_OPTION(v, klt_levels);
    RPVIO_OPTION(v, predict_rotation);
    RPVIO_OPTION(v, predict_plane_motion);
    RPVIO_OPTION(v, max_forward_backward_px);
    RPVIO_OPTION(v, missed_plane_frames);
    RPVIO_OPTION(v, klt_min_eigenvalue);
    RPVIO_OPTION(v, clahe);
    RPVIO_OPTION(v, ransac_threshold_px);
    RPVIO_OPTION(v, virtual_focal);
    RPVIO_OPTION(v, anchor_refinement);
    RPVIO_OPTION(v, max_warp_scale);
    RPVIO_OPTION(v, local_warps);
    RPVIO_OPTION(v, detection_level);
    RPVIO_OPTION(v, detection_cell_px);
    RPVIO_OPTION(v, min_cell_features);
    RPVIO_OPTION(v, ground_features);
    RPVIO_OPTION(v, pipelined);
    RPVIO_OPTION(v, frames_in_flight);
  }
  void validate(const OptionsLoader& loader) const;
  /// Reads the keys present in `section` (others keep their defaults).
  static TrackerOptions load(const IniFile& ini, const std::string& section) {
    return loadOptions<TrackerOptions>(ini, section);
  }
  std::string describe() const { return describeOptions(*this); }
};

class FeatureTracker {
 public:
  FeatureTracker(const CameraIntrinsics& camera, const TrackerOptions& options);

  /// Tracks into a new image (CV_8UC1). `mask`: plane labels of the same instant (CV_8UC1, same
  /// size; 0 = not a static plane, 255 = unknown), ignored without use_masks. A missing or
  /// wrong-size mask, an all-zero mask or a blank image yield no features and one log line.
  /// `R_cur_prev`, when given: the camera's rotation since the previous image (previous-camera
  /// coordinates to current ones), where KLT starts each track (predict_rotation). `down`, when
  /// given: gravity's direction in the camera, the ground tracks' horizon (ground_features).
  FeatureFrame track(double t, const cv::Mat& image, const cv::Mat& mask,
                     const Eigen::Matrix3d* R_cur_prev = nullptr,
                     const Eigen::Vector3d* down = nullptr);

  /// Messages about degraded input since the last call (each distinct message once).
  std::vector<std::string> takeWarnings();
  const TrackerOptions& options() const { return options_; }

 private:
  struct Track {
    int id, plane_id, length;
    cv::Point2f pixel, normalized;
    cv::Mat anchor;            // the part of its birth image its warped template can reach
    cv::Point2f anchor_pixel;  // where it was born, in the pixels of `anchor`
    cv::Point2f from;          // pixel in the previous frame
    cv::Matx22d warp = cv::Matx22d::eye();  // offsets around the birth pixel → current offsets
    int frames_plane_missed = 0;            // consecutive frames its plane was absent from the mask
  };
  using PlaneHomographies = std::map<int, cv::Matx33d>;  // plane → previous-to-current (pixels)
  struct PlaneMotions {
    PlaneHomographies pixels;
    std::map<int, Eigen::Matrix3d> normalized;  // the same, undistorted (8 inliers or more)
  };
  void warnOnce(const std::string& message);
  void undistort(std::vector<Track>& tracks) const;
  using Pyramid = std::vector<cv::Mat>;  // cv::buildOpticalFlowPyramid's, with derivatives
  std::vector<Track> propagate(const Pyramid& pyramid, const cv::Mat& mask,
                               const Eigen::Matrix3d* R_cur_prev, double dt);
  /// Where KLT starts each track: its pixel moved by the rotation `R_cur_prev`, or by its plane's
  /// homography at constant velocity (predict_plane_motion).
  std::vector<cv::Point2f> predictPixels(const Eigen::Matrix3d& R_cur_prev, double dt) const;
  void refineAgainstAnchors(std::vector<Track>& tracks, const PlaneHomographies& homographies,
                            const cv::Mat& image) const;
  PlaneMotions rejectOutliers(std::vector<Track>& tracks) const;
  /// Where new corners may go: detectable, not `taken` by a kept track, away from the border.
  cv::Mat& detectionMask(const cv::Mat& taken);
  /// The pyramid level corners are detected on in images `width` px wide (detection_level).
  int detectionLevel(int width) const;
  /// Up to `wanted` corners where `allowed`, `spacing` px apart, from `detector`, on `level`;
  /// `pyramid`, when given, is `image`'s KLT pyramid (its levels are not computed again).
  std::vector<cv::Point2f> detectCorners(CornerDetector& detector, const cv::Mat& image,
                                         const cv::Mat& allowed, int wanted, double spacing,
                                         int level, const Pyramid* pyramid = nullptr) const;
  /// detection_cell_px: corners for the cells holding fewer than min_cell_features `kept` tracks
  /// and `corners` (the whole image's pass), where `allowed` (which excludes the kept tracks'
  /// neighbourhoods) and min_distance from the corners, at most `wanted`.
  std::vector<cv::Point2f> detectInSparseCells(const cv::Mat& image, cv::Mat& allowed,
                                               const std::vector<cv::Point2f>& corners,
                                               const std::vector<Track>& kept, int wanted,
                                               int level);
  void computeUniformRegions(const cv::Mat& mask);
  FeatureFrame publish(double t, double dt);
  Track newTrack(int label, cv::Point2f corner, cv::Point2f normalized, const cv::Mat& image);

  CameraIntrinsics camera_;
  TrackerOptions options_;
  // The previous image's pyramid: built once per image, used by the forward pass into the next
  // image and the backward pass out of it. The current one is built into the buffers of the one
  // before (swapped), so no image-sized memory is allocated per frame.
  Pyramid previous_pyramid_, pyramid_;
  CornerDetector detector_;
  CornerDetector plane_detector_;  // on one dense plane's box (its own buffers: another size)
  CornerDetector cell_detector_;   // on one sparse cell (detection_cell_px)
  std::vector<Track> tracks_;      // current frame
  std::vector<Track> previous_;    // previous frame (same ids where tracked)
  double previous_t_ = 0;
  // The last interval's motion, for predict_plane_motion: each plane's homography (normalized
  // coordinates), the gyroscope's rotation and the interval's length.
  std::map<int, Eigen::Matrix3d> plane_motions_;
  std::optional<Eigen::Matrix3d> last_rotation_;
  double last_dt_ = 0;
  cv::Mat detectable_;  // plane pixels after the per-plane erosion
  cv::Mat trackable_;   // plane pixels with no other label within window_margin
  // Image-sized buffers kept between frames (no per-frame allocation): the neighbourhoods'
  // lowest and highest labels, the neighbourhoods of kept tracks, where corners may go.
  cv::Mat lowest_label_, highest_label_, taken_, allowed_, on_plane_;
  int next_id_ = 0;
  std::optional<GroundTracks> ground_;  // with ground_features
  std::vector<std::string> warnings_, warned_;
};

}  // namespace rpvio
