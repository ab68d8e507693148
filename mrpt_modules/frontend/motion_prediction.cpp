#include "mrpt_modules/frontend/motion_prediction.h"

#include <Eigen/SVD>

namespace rpvio {

std::vector<cv::Point2f> predictUnderHomographies(const std::vector<cv::Point2f>& pixels,
                                                  const std::vector<cv::Point2f>& normalized,
                                                  const std::vector<Eigen::Matrix3d>& H_cur_prev,
                                                  const CameraIntrinsics& camera) {
  std::vector<cv::Point2f> predicted = pixels;
  for (size_t i = 0; i < pixels.size(); ++i) {
    const Eigen::Vector3d x(normalized[i].x, normalized[i].y, 1);
    const Eigen::Vector3d moved = H_cur_prev[i] * x;
    if (moved.z() < 1e-3) continue;
    predicted[i].x += static_cast<float>(camera.fx * (moved.x() / moved.z() - x.x()));
    predicted[i].y += static_cast<float>(camera.fy * (moved.y() / moved.z() - x.y()));
  }
  return predicted;
}

Eigen::Matrix3d predictPlaneHomography(const Eigen::Matrix3d& H_last, const Eigen::Matrix3d& R_last,
                                       const Eigen::Matrix3d& R_next, double interval_ratio) {
  const Eigen::Vector3d sigma = Eigen::JacobiSVD<Eigen::Matrix3d>(H_last).singularValues();
  if (!(sigma(1) > 0)) return R_next;
  const double scale = (H_last.determinant() > 0 ? 1.0 : -1.0) / sigma(1);
  const Eigen::Matrix3d M = scale * H_last * R_last.transpose() - Eigen::Matrix3d::Identity();
  const double distance_ratio = 1 + M.trace();  // dₖ / dₖ₋₁
  if (!(distance_ratio > 0.1)) return R_next;
  return R_next * (Eigen::Matrix3d::Identity() + (interval_ratio / distance_ratio) * M);
}

}  // namespace rpvio
