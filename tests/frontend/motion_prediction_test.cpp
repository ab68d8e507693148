// The motion prediction (motion_prediction.h) against exact pinhole projections: the gyroscope's
// rotation, and a plane's homography at constant velocity.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "mrpt_modules/frontend/motion_prediction.h"

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
  const auto predicted = predictUnderHomographies(
      pixels, normalized, std::vector<Eigen::Matrix3d>(pixels.size(), R), c);
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
  const auto predicted = predictUnderHomographies(
      pixels, normalized, std::vector<Eigen::Matrix3d>(pixels.size(), R), c);
  EXPECT_EQ(predicted[0], pixels[0]);
}

/// A camera pose: world point X_w → camera coordinates R (X_w − c).
struct Pose {
  Eigen::Matrix3d R;
  Eigen::Vector3d c;
};

/// The homography of the plane nᵀX_w = d between the normalized coordinates of two cameras.
Eigen::Matrix3d planeHomography(const Pose& from, const Pose& to, const Eigen::Vector3d& n_w,
                                double d_w) {
  // In `from`'s coordinates the plane is n_fᵀX = d_f; X_to = R X + t.
  const Eigen::Matrix3d R = to.R * from.R.transpose();
  const Eigen::Vector3d t = to.R * (from.c - to.c);
  const Eigen::Vector3d n_f = from.R * n_w;
  const double d_f = d_w - n_w.dot(from.c);
  return R + t * n_f.transpose() / d_f;
}

Eigen::Matrix3d turn(double yaw, double pitch, double roll) {
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitX()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitZ()))
      .toRotationMatrix();
}

TEST(PlaneHomographyPrediction, ConstantVelocityAndAnyRotationsGiveTheExactNextHomography) {
  // A camera approaching a wall (its distance changes: the 1 + tr M term) and another flying over
  // a floor, each turning differently in the two intervals; the second interval 1.5x longer (a
  // dropped frame at another rate). The fitted homography comes at an arbitrary scale and sign.
  const Eigen::Vector3d v(0.8, -0.1, 1.6);  // m/s, world
  const double dt = 0.05;
  struct Case {
    Eigen::Vector3d n;
    double d;
  };
  for (const Case& plane :
       {Case{Eigen::Vector3d(0, 0, 1), 6.0}, Case{Eigen::Vector3d(0, -1, 0), 1.2}}) {
    const Pose a{turn(0.3, -0.2, 0.05), Eigen::Vector3d(0.2, 0.1, 0)};
    const Pose b{turn(0.15, 0.1, 0.0) * a.R, a.c + v * dt};
    const Pose c{turn(-0.2, 0.05, 0.1) * b.R, b.c + v * 1.5 * dt};
    const Eigen::Matrix3d H_ab = planeHomography(a, b, plane.n, plane.d);
    const Eigen::Matrix3d H_bc = planeHomography(b, c, plane.n, plane.d);
    const Eigen::Matrix3d predicted =
        predictPlaneHomography(-2.7 * H_ab, b.R * a.R.transpose(), c.R * b.R.transpose(), 1.5);
    // Up to scale: compare with both normalized to their (2, 2) entry.
    EXPECT_LT((predicted / predicted(2, 2) - H_bc / H_bc(2, 2)).norm(), 1e-9)
        << plane.n.transpose();
    // The translation matters: rotation alone is far from it.
    const Eigen::Matrix3d R_bc = c.R * b.R.transpose();
    EXPECT_GT((R_bc / R_bc(2, 2) - H_bc / H_bc(2, 2)).norm(), 0.01);
  }
}

TEST(PlaneHomographyPrediction, APlaneTheCameraCrossedFallsBackToTheRotation) {
  // M = H Rᵀ − I with tr M = −0.95: the plane's distance shrank to 5 % (a fit gone wrong).
  const Eigen::Matrix3d R_last = turn(0.1, 0, 0), R_next = turn(0.05, 0.02, 0);
  Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
  M(2, 2) = -0.95;
  const Eigen::Matrix3d H_last = (Eigen::Matrix3d::Identity() + M) * R_last;
  EXPECT_LT((predictPlaneHomography(H_last, R_last, R_next, 1.0) - R_next).norm(), 1e-12);
}

}  // namespace
}  // namespace rpvio
