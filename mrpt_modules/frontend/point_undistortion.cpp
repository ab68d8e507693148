#include "mrpt_modules/frontend/point_undistortion.h"

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

}  // namespace rpvio
