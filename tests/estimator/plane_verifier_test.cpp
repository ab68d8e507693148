// PlaneVerifier on exact geometry with tracker-like noise: a camera turning and moving sideways
// past a wall and a floor (static) and a panel driving towards it (moving); the panel is rejected
// within a second, the static planes never; a panel moving along the camera's own translation
// keeps its epipoles and is not (the documented limit).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "mrpt_modules/estimator/plane_verifier.h"

namespace rpvio {
namespace {

constexpr int kWall = 1, kFloor = 2, kPanel = 3;
constexpr double kRate = 20, kYawRate = 0.4, kSpeed = 1.0;  // Hz, rad/s, m/s

Eigen::Matrix3d cameraRotation(double t) {  // world from camera: yaw about the camera's y axis
  return Eigen::AngleAxisd(kYawRate * t, Eigen::Vector3d::UnitY()).toRotationMatrix();
}
Eigen::Vector3d cameraPosition(double t) { return {kSpeed * t, 0, 0.3 * t}; }

struct ScenePoint {
  int id, plane;
  Eigen::Vector3d at_t0;
};

std::vector<ScenePoint> scene() {
  std::vector<ScenePoint> points;
  int id = 0;
  for (double x = -3; x <= 4; x += 0.5)  // wall at z = 6 (camera y points down)
    for (double y = -1.5; y <= 1.0; y += 0.5) points.push_back({id++, kWall, {x, y, 6}});
  for (double x = -2; x <= 3; x += 0.5)  // floor 1.5 m below the camera
    for (double z = 2; z <= 5; z += 0.5) points.push_back({id++, kFloor, {x, 1.5, z}});
  for (double x = 0.6; x <= 1.6; x += 0.25)  // panel at z = 4.5
    for (double y = -0.8; y <= 0.4; y += 0.3) points.push_back({id++, kPanel, {x, y, 4.5}});
  return points;
}

/// Runs 1.5 s of frames through the verifier; the panel moves with `panel_velocity` (world).
PlaneVerifier run(const Eigen::Vector3d& panel_velocity, bool enabled = true) {
  PlaneVerifierOptions options;
  options.enabled = enabled;
  PlaneVerifier verifier(options);
  std::mt19937 rng(3);
  std::normal_distribution<double> pixel_noise(0, 0.2 / options.focal_px);
  const std::vector<ScenePoint> points = scene();
  for (int k = 0; k <= 1.5 * kRate; ++k) {
    const double t = k / kRate;
    FeatureFrame frame;
    frame.t = t;
    for (const ScenePoint& p : points) {
      const Eigen::Vector3d X = p.at_t0 + (p.plane == kPanel ? Eigen::Vector3d(panel_velocity * t)
                                                             : Eigen::Vector3d::Zero().eval());
      const Eigen::Vector3d X_c = cameraRotation(t).transpose() * (X - cameraPosition(t));
      if (X_c.z() < 0.5 || std::abs(X_c.x() / X_c.z()) > 0.8 || std::abs(X_c.y() / X_c.z()) > 0.6)
        continue;
      TrackedFeature f;
      f.id = p.id;
      f.plane_id = p.plane;
      f.normalized = X_c.hnormalized() + Eigen::Vector2d(pixel_noise(rng), pixel_noise(rng));
      frame.features.push_back(f);
    }
    const Eigen::Quaterniond R_previous_current(
        cameraRotation(std::max(0.0, t - 1 / kRate)).transpose() * cameraRotation(t));
    const FeatureFrame kept = verifier.filter(frame, R_previous_current);
    for (const TrackedFeature& f : kept.features)
      EXPECT_FALSE(verifier.rejected().count(f.plane_id)) << "a rejected plane's feature kept";
  }
  return verifier;
}

TEST(PlaneVerifier, APanelDrivingTowardsTheCameraIsRejectedTheWallAndFloorAreNot) {
  const PlaneVerifier verifier = run(Eigen::Vector3d(0, 0, -1.0));
  ASSERT_EQ(verifier.rejections().size(), 1u);
  EXPECT_EQ(verifier.rejections()[0].plane_id, kPanel);
  // First check at 0.3 s, rejected on the third disagreement.
  EXPECT_LE(verifier.rejections()[0].t, 0.45 + 1e-9);
  EXPECT_GT(verifier.rejections()[0].error_px, 1.0);
}

TEST(PlaneVerifier, StaticPanelIsKept) {
  EXPECT_TRUE(run(Eigen::Vector3d::Zero()).rejections().empty());
}

TEST(PlaneVerifier, APanelMovingAlongTheCamerasTranslationPasses) {
  // Same direction as the camera's (1, 0, 0.3) m/s: the epipoles do not change.
  EXPECT_TRUE(run(Eigen::Vector3d(0.5, 0, 0.15)).rejections().empty());
}

TEST(PlaneVerifier, DisabledLeavesFramesAlone) {
  EXPECT_TRUE(run(Eigen::Vector3d(0, 0, -1.0), false).rejections().empty());
}

}  // namespace
}  // namespace rpvio
