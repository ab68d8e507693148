#include "mrpt_modules/frontend/point_undistortion.h"

#include <cmath>
#include <opencv2/calib3d.hpp>

namespace rpvio {

std::vector<cv::Point2f> undistortToNormalized(const std::vector<cv::Point2f>& pixels,
                                               const CameraIntrinsics& cam) {
  std::vector<cv::Point2f> out;
  if (pixels.empty()) return out;
  if (cam.model == DistortionModel::None) {
    for (const auto& p : pixels)
      out.emplace_back(static_cast<float>((p.x - cam.cx) / cam.fx),
                       static_cast<float>((p.y - cam.cy) / cam.fy));
    return out;
  }
  const cv::Matx33d K(cam.fx, 0, cam.cx, 0, cam.fy, cam.cy, 0, 0, 1);
  const cv::Vec4d D(cam.distortion[0], cam.distortion[1], cam.distortion[2], cam.distortion[3]);
  if (cam.model == DistortionModel::Equidistant) {
    cv::fisheye::undistortPoints(pixels, out, K, D);
  } else {
    cv::undistortPoints(pixels, out, K, D);
  }
  return out;
}

Eigen::Vector2d distortToPixel(const Eigen::Vector2d& x, const CameraIntrinsics& camera) {
  const auto& k = camera.distortion;
  Eigen::Vector2d d = x;
  const double r2 = x.squaredNorm();
  if (camera.model == DistortionModel::RadTan) {
    const double radial = 1 + k[0] * r2 + k[1] * r2 * r2;
    d = {x.x() * radial + 2 * k[2] * x.x() * x.y() + k[3] * (r2 + 2 * x.x() * x.x()),
         x.y() * radial + k[2] * (r2 + 2 * x.y() * x.y()) + 2 * k[3] * x.x() * x.y()};
  } else if (camera.model == DistortionModel::Equidistant && r2 > 1e-18) {
    const double r = std::sqrt(r2), theta = std::atan(r), t2 = theta * theta;
    const double theta_d = theta * (1 + t2 * (k[0] + t2 * (k[1] + t2 * (k[2] + t2 * k[3]))));
    d = x * (theta_d / r);
  }
  return {camera.fx * d.x() + camera.cx, camera.fy * d.y() + camera.cy};
}

}  // namespace rpvio
