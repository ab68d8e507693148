#include "mrpt_modules/frontend/rotation_prediction.h"

namespace rpvio {

std::vector<cv::Point2f> predictUnderRotation(const std::vector<cv::Point2f>& pixels,
                                              const std::vector<cv::Point2f>& normalized,
                                              const Eigen::Matrix3d& R_cur_prev,
                                              const CameraIntrinsics& camera) {
  std::vector<cv::Point2f> predicted = pixels;
  for (size_t i = 0; i < pixels.size(); ++i) {
    const Eigen::Vector3d x(normalized[i].x, normalized[i].y, 1);
    const Eigen::Vector3d turned = R_cur_prev * x;
    if (turned.z() < 1e-3) continue;
    predicted[i].x += static_cast<float>(camera.fx * (turned.x() / turned.z() - x.x()));
    predicted[i].y += static_cast<float>(camera.fy * (turned.y() / turned.z() - x.y()));
  }
  return predicted;
}

}  // namespace rpvio
