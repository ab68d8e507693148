#pragma once
// A camera pose from known 3D points and their normalized observations (PnP), for the window frames
// that are not part of the initial pair.
#include <optional>
#include <vector>

#include "mrpt_modules/initialization/camera_pose.h"

namespace rpvio {

struct PnpOptions {
  size_t min_points = 8;
  double ransac_threshold_px = 3.0;  // at the virtual focal length
  double virtual_focal = 460.0;
  double min_inlier_ratio = 0.3;
};

/// Pose of the camera that sees points_r[k] (reference frame) at normalized u[k]. With `guess`
/// (e.g. the neighbouring frame's pose) an iterative solve from it, otherwise EPnP inside RANSAC;
/// both end with a Levenberg–Marquardt refinement on the inliers. nullopt when there are too few
/// points or inliers. `inlier` (optional) receives which points agree with the pose.
std::optional<CameraPose> cameraPoseFromPnp(const std::vector<Eigen::Vector3d>& points_r,
                                            const std::vector<Eigen::Vector2d>& u,
                                            const std::optional<CameraPose>& guess,
                                            const PnpOptions& options = {},
                                            std::vector<bool>* inlier = nullptr);

}  // namespace rpvio
