// A camera's position from points when its rotation is known (camera_pnp.h), and the window
// structure placing a frame that sees too few points for a PnP that way (window_structure.h).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "mrpt_modules/initialization/camera_pnp.h"
#include "mrpt_modules/initialization/window_structure.h"

namespace rpvio {
namespace {

CameraPose poseOf(double yaw, const Eigen::Vector3d& p) {
  // A camera looking along the reference's z, turned about its y axis (a car's yaw).
  return CameraPose{Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitY()).toRotationMatrix(), p};
}

Eigen::Vector2d project(const CameraPose& camera, const Eigen::Vector3d& X_r) {
  return camera.toCamera(X_r).hnormalized();
}

/// Points 4–12 m in front of the reference camera, spread over its view.
std::vector<Eigen::Vector3d> pointsAhead(size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> side(-3, 3), depth(4, 12);
  std::vector<Eigen::Vector3d> points;
  for (size_t k = 0; k < n; ++k) points.emplace_back(side(rng), 0.5 * side(rng), depth(rng));
  return points;
}

TEST(CameraPositionFromKnownRotation, ThreePointsGiveThePosition) {
  const CameraPose truth = poseOf(0.1, Eigen::Vector3d(0.3, -0.1, 1.2));
  const auto points = pointsAhead(3, 1);
  std::vector<Eigen::Vector2d> u;
  for (const auto& X : points) u.push_back(project(truth, X));
  const auto found = cameraPositionFromKnownRotation(points, u, truth.R_r_c, 3);
  ASSERT_TRUE(found);
  EXPECT_LT((found->p_r_c - truth.p_r_c).norm(), 1e-9);
  EXPECT_TRUE(found->R_r_c.isApprox(truth.R_r_c));
}

TEST(CameraPositionFromKnownRotation, AWrongPointIsLeftOut) {
  const CameraPose truth = poseOf(-0.05, Eigen::Vector3d(-0.2, 0.05, 0.8));
  const auto points = pointsAhead(6, 2);
  std::vector<Eigen::Vector2d> u;
  for (const auto& X : points) u.push_back(project(truth, X));
  u[4].x() += 20.0 / 460;  // a track that slid 20 px
  std::vector<bool> inlier;
  const auto found = cameraPositionFromKnownRotation(points, u, truth.R_r_c, 3, {}, &inlier);
  ASSERT_TRUE(found);
  EXPECT_LT((found->p_r_c - truth.p_r_c).norm(), 1e-9);
  EXPECT_EQ(inlier, std::vector<bool>({true, true, true, true, false, true}));
}

TEST(CameraPositionFromKnownRotation, TooFewPointsOrOneRayDoNotPlaceIt) {
  const CameraPose truth = poseOf(0, Eigen::Vector3d(0, 0, 1));
  auto points = pointsAhead(3, 3);
  std::vector<Eigen::Vector2d> u;
  for (const auto& X : points) u.push_back(project(truth, X));
  EXPECT_FALSE(cameraPositionFromKnownRotation(points, u, truth.R_r_c, 4));  // 3 of 4 needed
  // Three points on one ray of the camera: its position along that ray is free.
  for (int k = 0; k < 3; ++k) points[k] = truth.toReference(Eigen::Vector3d(0.1, 0.2, 1) * (k + 2));
  u.assign(3, Eigen::Vector2d(0.1, 0.2));
  EXPECT_FALSE(cameraPositionFromKnownRotation(points, u, truth.R_r_c, 3));
}

/// Three frames driving forward: the pair (0, 2) sees 40 points, frame 1 only 5 of them.
struct ThreeFrames {
  std::vector<CameraPose> truth = {poseOf(0, Eigen::Vector3d::Zero()),
                                   poseOf(0.03, Eigen::Vector3d(0.05, 0, 0.6)),
                                   poseOf(0.08, Eigen::Vector3d(0.15, 0, 1.2))};
  SfmWindow window;

  ThreeFrames() {
    window.cameras.resize(3);
    const auto points = pointsAhead(40, 4);
    for (size_t k = 0; k < points.size(); ++k) {
      SfmTrack track;
      track.feature_id = static_cast<int>(k);
      for (size_t f : {0, 1, 2})
        if (f != 1 || k < 5) track.observations.push_back({f, project(truth[f], points[k])});
      window.tracks.push_back(track);
    }
  }
  /// X_cb = R X_ca, as the gyroscope gives it.
  Eigen::Matrix3d rotation(size_t a, size_t b) const {
    return truth[b].R_r_c.transpose() * truth[a].R_r_c;
  }
};

TEST(WindowStructure, AFrameWithTooFewPointsForAPnpIsPlacedWithTheGyroscopesRotation) {
  ThreeFrames without;
  std::string why;
  EXPECT_FALSE(buildWindowStructure(without.window, 0, 2, without.truth[2], {}, &why));
  EXPECT_EQ(why, "structure lost at window frame 1");

  ThreeFrames with;
  WindowStructureOptions options;
  options.camera_rotation = [&](size_t a, size_t b) { return with.rotation(a, b); };
  ASSERT_TRUE(buildWindowStructure(with.window, 0, 2, with.truth[2], options, &why)) << why;
  ASSERT_TRUE(with.window.cameras[1]);
  EXPECT_LT((with.window.cameras[1]->p_r_c - with.truth[1].p_r_c).norm(), 1e-6);
  EXPECT_TRUE(with.window.cameras[1]->R_r_c.isApprox(with.truth[1].R_r_c, 1e-9));
}

}  // namespace
}  // namespace rpvio
