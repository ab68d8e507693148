#pragma once
// Where features should appear after the camera's rotation between two images (the gyroscope's):
// a bearing x turns into R x, the pinhole flow of that turn is
//   Δu = K π(R x) − K π(x),  π(x) = (x/z, y/z)  (the infinite homography K R K⁻¹),
// added to each feature's pixel. KLT starts there, so a fast turn needs no deep pyramid; what is
// left is the flow of the translation (and the lens distortion's share of the turn's flow).
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "common/sensor_types.h"

namespace rpvio {

/// `pixels` and their undistorted `normalized` coordinates in the previous image; `R_cur_prev`
/// maps previous-camera coordinates to current-camera ones. A bearing turned behind the camera
/// keeps its pixel.
std::vector<cv::Point2f> predictUnderRotation(const std::vector<cv::Point2f>& pixels,
                                              const std::vector<cv::Point2f>& normalized,
                                              const Eigen::Matrix3d& R_cur_prev,
                                              const CameraIntrinsics& camera);

}  // namespace rpvio
