#pragma once
// Pixel → undistorted normalized image coordinates (z = 1), for the radtan (Brown-Conrady) and
// equidistant (Kannala-Brandt) models of the calibration. Features are undistorted, images never.
#include <opencv2/core.hpp>
#include <vector>

#include "common/sensor_types.h"

namespace rpvio {

std::vector<cv::Point2f> undistortToNormalized(const std::vector<cv::Point2f>& pixels,
                                               const CameraIntrinsics& camera);

}  // namespace rpvio
