#pragma once
// Geometric outlier rejection between consecutive frames (DESIGN.md §1 step 1): per static plane,
// a homography fitted by RANSAC; without masks, a fundamental matrix. Both on normalized
// coordinates re-projected to a virtual camera of focal `virtual_focal`, so the threshold is in
// pixels whatever the real camera.
#include <opencv2/core.hpp>
#include <vector>

namespace rpvio {

struct RansacOptions {
  double threshold_px = 1.0;
  double virtual_focal = 460.0;
  double confidence = 0.99;
  // Homography: refit the best hypothesis's inliers (LO-RANSAC) for an accurate H. Off in the
  // tracker: the refit also keeps tracks up to the threshold from the refined plane motion, and
  // that measured worse on the simulator suite than the minimal model's stricter inliers.
  bool refine_homography = false;
};

/// Inlier flags of the homography RANSAC between matched normalized points (≥ 4 matches; with
/// fewer, every point is kept). Returns in `H`, if given, the least-squares homography of the
/// inliers (virtual-camera pixels).
std::vector<bool> homographyInliers(const std::vector<cv::Point2f>& from,
                                    const std::vector<cv::Point2f>& to,
                                    const RansacOptions& options, cv::Mat* H = nullptr);

/// Inlier flags of the fundamental-matrix RANSAC (≥ 8 matches; with fewer, all kept).
std::vector<bool> fundamentalInliers(const std::vector<cv::Point2f>& from,
                                     const std::vector<cv::Point2f>& to,
                                     const RansacOptions& options);

}  // namespace rpvio
