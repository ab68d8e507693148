// The rotation prediction (rotation_prediction.h) against exact pinhole projections.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "mrpt_modules/frontend/rotation_prediction.h"

namespace rpvio {
namespace {

// 640x480, fx 400, fy 410, principal point at the centre, no distortion.
CameraIntrinsics camera() { return {640, 480, 400, 410, 320, 240}; }

cv::Point2f project(const CameraIntrinsics& c, const Eigen::Vector3d& X) {
  return {static_cast<float>(c.fx * X.x() / X.z() + c.cx),
          static_cast<float>(c.fy * X.y() / X.z() + c.cy)};
}

TEST(RotationPrediction, PureRotationLandsOnTheExactProjection) {
  // Points at any depth: a pure rotation moves their pixels independently of it.
  const CameraIntrinsics c = camera();
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.10, Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(-0.05, Eigen::Vector3d::UnitX()) *
                             Eigen::AngleAxisd(0.08, Eigen::Vector3d::UnitZ()))
                                .toRotationMatrix();
  std::vector<cv::Point2f> pixels, normalized;
  std::vector<Eigen::Vector3d> points;
  for (double x : {-2.0, 0.0, 1.5})
    for (double y : {-1.0, 0.5})
      for (double z : {2.0, 9.0}) {
        points.emplace_back(x, y, z);
        pixels.push_back(project(c, points.back()));
        normalized.emplace_back(static_cast<float>(x / z), static_cast<float>(y / z));
      }
  const auto predicted = predictUnderRotation(pixels, normalized, R, c);
  double largest_motion = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    const cv::Point2f exact = project(c, R * points[i]);
    EXPECT_LT(cv::norm(predicted[i] - exact), 1e-3) << i;
    largest_motion = std::max(largest_motion, cv::norm(exact - pixels[i]));
  }
  EXPECT_GT(largest_motion, 40);  // the rotation moves pixels far beyond a KLT window
}

TEST(RotationPrediction, ABearingTurnedBehindTheCameraKeepsItsPixel) {
  const CameraIntrinsics c = camera();
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(M_PI / 2 + 0.2, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const std::vector<cv::Point2f> pixels{{320, 240}}, normalized{{0, 0}};
  const auto predicted = predictUnderRotation(pixels, normalized, R, c);
  EXPECT_EQ(predicted[0], pixels[0]);
}

}  // namespace
}  // namespace rpvio
