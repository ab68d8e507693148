#pragma once
// Pixel ↔ undistorted normalized image coordinates (z = 1), for the radtan (Brown-Conrady) and
// equidistant (Kannala-Brandt) models of the calibration. Features are undistorted, images never.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "common/sensor_types.h"

namespace rpvio {

std::vector<cv::Point2f> undistortToNormalized(const std::vector<cv::Point2f>& pixels,
                                               const CameraIntrinsics& camera);
/// Undistorted normalized coordinates (z = 1) → pixel: the calibration's lens model, then K.
Eigen::Vector2d distortToPixel(const Eigen::Vector2d& normalized, const CameraIntrinsics& camera);

}  // namespace rpvio
