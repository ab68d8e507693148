#pragma once
// The ground's homography between two images by direct (photometric) alignment. A street's asphalt
// has few corners KLT can follow at a car's speed (docs/notes/2026-12-05-real-street-images.md),
// but its pixels' gradients, taken together, fix the homography the ground induces:
//   x_cur ~ H x_prev,  H = R + a nᵀ                                                        (1)
// (undistorted normalized coordinates; R the gyroscope's rotation, n the ground's unit normal in
// the previous camera, towards the ground; a = t/d, the camera's translation in the current
// camera over its height). Unknowns: a (3), n (2, on the sphere) and an affine brightness change
// I_cur(w(x)) ≈ α I_prev(x) + β (auto-exposure), found coarse to fine by Levenberg-Marquardt with
// Huber weights over the pixels of the previous image that look below the horizon and have a
// gradient.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "common/sensor_types.h"

namespace rpvio {

/// The ground's motion between two images, (1).
struct GroundMotion {
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  Eigen::Vector3d n = Eigen::Vector3d::UnitY();
  Eigen::Matrix3d homography(const Eigen::Matrix3d& R) const { return R + a * n.transpose(); }
};

struct GroundAlignmentOptions {
  double horizon_margin_deg = 8;  // pixels looking at least this far below the horizon
  // ... and at a ground point at most this many heights to the side of the camera's heading (the
  // road's corridor, not the parked cars and facades beside it)
  double corridor_heights = 2;
  int coarsest_level = 4;  // pyramid levels the alignment starts / ends on
  int finest_level = 2;
  int iterations = 12;                // per level
  double min_gradient = 3;            // grey levels per pixel of the level
  int max_pixels = 600;               // per level, evenly thinned beyond
  int min_pixels = 200;               // on the finest level, else no alignment
  double max_residual_grey = 12;      // robust RMS of the brightness error where it converged
  double min_inlier_share = 0.6;      // pixels whose brightness error is within the robust scale
  double max_still_cost_ratio = 0.5;  // the alignment explains half the images' difference
  double max_normal_tilt_deg = 25;    // n from the given down direction: else not the ground
  double max_heights_per_image = 2;   // |a|: a car at 30 m/s, 10 Hz, 1.5 m high moves 2 heights
};

/// An image pyramid: level 0 the image, each next one cv::pyrDown of it.
using GreyPyramid = std::vector<cv::Mat>;
GreyPyramid buildGreyPyramid(const cv::Mat& image, int levels);

class GroundAligner {
 public:
  GroundAligner(const CameraIntrinsics& camera, const GroundAlignmentOptions& options);

  struct Result {
    bool ok = false;
    GroundMotion motion;
    double residual_grey = 0;     // robust RMS on the finest level
    int pixels = 0;               // used on the finest level
    double inlier_share = 0;      // of those, within the robust scale of the brightness error
    double still_cost_ratio = 1;  // the robust cost over that of the rotation alone
  };
  /// The ground's motion from `previous` to `current` (pyramids of the same size, at least
  /// coarsest_level + 1 levels), `R_cur_prev` the camera's rotation, `down` the direction of
  /// gravity in the previous camera (unit): the horizon, the normal's prior and its starting
  /// point. Starts from `guess` when given, and from motions along the camera's axes at several
  /// speeds, whichever fits best on the coarsest level.
  Result align(const GreyPyramid& previous, const GreyPyramid& current,
               const Eigen::Matrix3d& R_cur_prev, const Eigen::Vector3d& down,
               const GroundMotion* guess);

 private:
  struct Sample {
    Eigen::Vector3d x;  // normalized bearing, z = 1
    float grey;         // previous image
  };
  /// The previous image's gradient pixels below the horizon on `level`.
  std::vector<Sample> samples(const cv::Mat& previous, int level, const Eigen::Vector3d& down);
  /// y = H x and its pixel p in `image` of `level`; false when behind the camera or outside.
  bool warp(const Eigen::Matrix3d& H, const Eigen::Vector3d& x, const cv::Mat& image, int level,
            Eigen::Vector3d& y, Eigen::Vector2d& p) const;
  /// Robust cost of `motion` (brightness gain and offset α, β) over `samples` into `current`.
  double cost(const std::vector<Sample>& samples, const cv::Mat& current, int level,
              const Eigen::Matrix3d& R, const GroundMotion& motion, double alpha,
              double beta) const;

  CameraIntrinsics camera_;
  GroundAlignmentOptions options_;
  Eigen::Vector3d down_ = Eigen::Vector3d::UnitY();  // of the alignment under way
  std::vector<cv::Mat> normalized_;  // per level: each pixel's undistorted coordinates (CV_32FC2)
};

}  // namespace rpvio
