#pragma once
// A camera pose from known 3D points and their normalized observations (PnP), for the window frames
// that are not part of the initial pair; or its position alone when its rotation is known.
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

constexpr size_t kMaxKnownRotationHypothesisPoints = 40;

/// The camera of rotation R_r_c (known, e.g. the gyroscope's from a located neighbour) that sees
/// points_r[k] at normalized u[k]: each point gives two linear equations in its position p,
/// [u; 1]× R_r_cᵀ (X − p) = 0. Solved for every pair of points (the first
/// kMaxKnownRotationHypothesisPoints) as hypotheses, the one most points agree with (reprojection
/// within options.ransac_threshold_px, in front) kept, then solved on those. Two points suffice
/// where a full PnP needs options.min_points: nullopt with fewer than `min_points` points or
/// inliers, or inliers under options.min_inlier_ratio of them. `inlier` as above.
std::optional<CameraPose> cameraPositionFromKnownRotation(
    const std::vector<Eigen::Vector3d>& points_r, const std::vector<Eigen::Vector2d>& u,
    const Eigen::Matrix3d& R_r_c, size_t min_points, const PnpOptions& options = {},
    std::vector<bool>* inlier = nullptr);

}  // namespace rpvio
