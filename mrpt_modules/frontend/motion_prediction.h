#pragma once
// Where features should appear in the next image, from the camera's motion since the previous
// one. A bearing x of the previous camera moves to H x: the gyroscope's rotation R (the infinite
// homography), or for a point of a plane its homography with the predicted motion. The pixel flow
//   Δu = K π(H x) − K π(x),  π(x) = (x/z, y/z)
// is added to each feature's pixel; KLT starts there, so a fast turn (or, on a plane, fast
// translation) needs no deep pyramid. What is left is the prediction's error (and the lens
// distortion's share of the flow).
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "common/sensor_types.h"

namespace rpvio {

/// `pixels` and their undistorted `normalized` coordinates in the previous image; `H_cur_prev[i]`
/// maps point i's previous bearing to its current one. A bearing sent behind the camera keeps its
/// pixel.
std::vector<cv::Point2f> predictUnderHomographies(const std::vector<cv::Point2f>& pixels,
                                                  const std::vector<cv::Point2f>& normalized,
                                                  const std::vector<Eigen::Matrix3d>& H_cur_prev,
                                                  const CameraIntrinsics& camera);

/// A static plane's homography over the next interval (normalized coordinates), from the one it
/// had over the last interval at constant velocity.
/// - `H_last` (frames k−1 → k, any scale): R_last + t nₖ₋₁ᵀ/dₖ₋₁, with t the translation in
///   frame k; scaled so that its middle singular value is 1 and det > 0 (a Euclidean
///   homography's σ₂ is 1; det = 1 + nₖ₋₁ᵀR_lastᵀt/dₖ₋₁ > 0 while the camera stays on its side).
/// - `R_last`, `R_next`: the camera's rotations over the two intervals (the gyroscope's).
/// - M = H_last R_lastᵀ − I = t nₖᵀ/dₖ₋₁ (nₖ = R_last nₖ₋₁); the plane's distance in frame k is
///   dₖ = dₖ₋₁ + nₖᵀt = dₖ₋₁ (1 + tr M).
/// - At constant velocity in the world the next translation is R_next · s t (s: the ratio of
///   the intervals), so H_next = R_next (I + s M / (1 + tr M)): exact for any rotations.
/// Returns R_next alone when M cannot be trusted (the plane behind or crossed: 1 + tr M ≤ 0.1).
Eigen::Matrix3d predictPlaneHomography(const Eigen::Matrix3d& H_last, const Eigen::Matrix3d& R_last,
                                       const Eigen::Matrix3d& R_next, double interval_ratio);

}  // namespace rpvio
