#pragma once
// RP-VIO's initial two-view geometry (DESIGN.md §1 step 3): a homography between two frames on the
// normalized coordinates of one plane's features, its decomposition (Malis & Vargas 2007) into up
// to four (R, t/d, n), the positive-depth test, and the choice of the solution whose rotation is
// closest to the gyroscope's.
#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

namespace rpvio {

/// Camera motion and plane from frame i to frame j: X_j = R X_i + t, plane n·X_i = d (camera i),
/// t_over_d = t / d. R, t map points of camera i into camera j (OpenCV's convention).
struct PlaneMotion {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t_over_d = Eigen::Vector3d::Zero();
  Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
  double rotation_error_deg = 0;  // angle between R and the gyroscope's prediction
  size_t inliers = 0;
};

struct HomographyInitOptions {
  double ransac_threshold_px = 1.0;  // at the virtual focal length
  double virtual_focal = 460.0;
  size_t min_inliers = 20;
};

/// Decomposes H (normalized coordinates, x_j ~ H x_i) and keeps the solutions with the plane in
/// front of camera i for the given bearings (n·x_i > 0 for all of them).
std::vector<PlaneMotion> decomposePlaneHomography(const Eigen::Matrix3d& H,
                                                  const std::vector<Eigen::Vector2d>& points_i);

/// Full step: homography RANSAC on the matches, decomposition, positive-depth test, and the
/// solution whose rotation is closest to `R_gyro` (X_j = R_gyro X_i, the preintegrated rotation
/// moved to the camera frame). Empty with a reason when it cannot decide.
std::optional<PlaneMotion> planeMotionFromHomography(
    const std::vector<Eigen::Vector2d>& points_i, const std::vector<Eigen::Vector2d>& points_j,
    const Eigen::Matrix3d& R_gyro, const HomographyInitOptions& options,
    std::string* why_not = nullptr, std::vector<PlaneMotion>* candidates = nullptr);

/// The camera-frame rotation X_cj = R X_ci implied by the body rotation ΔR_ij = R_wbiᵀ R_wbj and
/// the camera mount R_BC.
Eigen::Matrix3d cameraRotationFromBody(const Eigen::Matrix3d& delta_R_body,
                                       const Eigen::Matrix3d& R_BC);

}  // namespace rpvio
