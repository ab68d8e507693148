#include "mrpt_modules/loop/keyframe_appearance.h"

#include <opencv2/features2d.hpp>

#include "mrpt_modules/frontend/point_undistortion.h"

namespace rpvio {

KeyframeAppearance describeKeyframe(const cv::Mat& image,
                                    const std::vector<AppearancePoint>& tracked,
                                    const CameraIntrinsics& camera, int corners) {
  constexpr float kPatch = 31;  // px, ORB's patch
  const auto orb = cv::ORB::create(corners, 1.2f, /*nlevels=*/1, /*edgeThreshold=*/31,
                                   /*firstLevel=*/0, /*WTA_K=*/2, cv::ORB::HARRIS_SCORE,
                                   /*patchSize=*/31, /*fastThreshold=*/20);
  std::vector<cv::KeyPoint> keypoints;
  orb->detect(image, keypoints);
  for (auto& k : keypoints) k.angle = 0, k.class_id = -1;
  for (size_t i = 0; i < tracked.size(); ++i) {
    const Eigen::Vector2d pixel = distortToPixel(tracked[i].normalized, camera);
    keypoints.emplace_back(
        cv::Point2f(static_cast<float>(pixel.x()), static_cast<float>(pixel.y())), kPatch, 0.f, 0.f,
        0, static_cast<int>(i));
  }
  KeyframeAppearance out;
  orb->compute(image, keypoints, out.descriptors);  // drops the keypoints near the border
  std::vector<cv::Point2f> corner_pixels;
  for (const auto& k : keypoints)
    if (k.class_id < 0) corner_pixels.push_back(k.pt);
  const std::vector<cv::Point2f> corner_normalized = undistortToNormalized(corner_pixels, camera);
  size_t next_corner = 0;
  for (const auto& k : keypoints) {
    if (k.class_id >= 0) {
      out.points.push_back(tracked[k.class_id]);
    } else {
      const cv::Point2f& x = corner_normalized[next_corner++];
      out.points.push_back({Eigen::Vector2d(x.x, x.y), std::nullopt, 0});
    }
  }
  return out;
}

}  // namespace rpvio
