#pragma once
// The VINS-style initial two-view geometry: the essential matrix by 5-point RANSAC (Nistér 2004,
// cv::findEssentialMat) on normalized coordinates and the relative pose with the most points in
// front of both cameras (cv::recoverPose).
#include <optional>
#include <string>
#include <vector>

#include "mrpt_modules/initialization/camera_pose.h"

namespace rpvio {

struct EssentialOptions {
  double ransac_threshold_px = 1.0;  // at the virtual focal length
  double virtual_focal = 460.0;
  size_t min_inliers = 12;
};

/// Pose of camera j in camera i (unit baseline ‖p_i_j‖ = 1) and which matches are inliers.
struct RelativePose {
  CameraPose i_j;
  std::vector<bool> inlier;
  size_t inliers = 0;
};

std::optional<RelativePose> relativePoseFromEssential(const std::vector<Eigen::Vector2d>& u_i,
                                                      const std::vector<Eigen::Vector2d>& u_j,
                                                      const EssentialOptions& options,
                                                      std::string* why_not = nullptr);

}  // namespace rpvio
