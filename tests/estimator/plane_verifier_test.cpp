// PlaneVerifier on exact geometry with tracker-like noise: a camera turning and moving sideways
// past a wall and a floor (static) and a panel driving towards it (moving); the panel is rejected
// within a second, the static planes never; a panel moving along the camera's own translation
// keeps its epipoles and is not (the documented limit). Frames given earlier are screened again.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

#include "mrpt_modules/estimator/plane_verifier.h"
#include "tests/estimator/wall_floor_panel_scene.h"

namespace rpvio {
namespace {

using namespace test;         // the scene
constexpr double kRate = 20;  // Hz

/// Runs 1.5 s of frames through the verifier; the panel moves with `panel_velocity` (world).
PlaneVerifier run(const Eigen::Vector3d& panel_velocity, bool enabled = true) {
  PlaneVerifierOptions options;
  options.enabled = enabled;
  PlaneVerifier verifier(options);
  std::mt19937 rng(3);
  std::normal_distribution<double> pixel_noise(0, 0.2 / options.focal_px);
  const WallFloorPanel scene;
  const std::vector<ScenePoint> points = scene.points();
  for (int k = 0; k <= 1.5 * kRate; ++k) {
    const double t = k / kRate;
    FeatureFrame frame;
    frame.t = t;
    for (const ScenePoint& p : points) {
      const Eigen::Vector3d X = p.at_t0 + (p.plane == kPanel ? Eigen::Vector3d(panel_velocity * t)
                                                             : Eigen::Vector3d::Zero().eval());
      const auto u = scene.project(t, X);
      if (!u) continue;
      TrackedFeature f;
      f.id = p.id;
      f.plane_id = p.plane;
      f.normalized = *u + Eigen::Vector2d(pixel_noise(rng), pixel_noise(rng));
      frame.features.push_back(f);
    }
    const Eigen::Quaterniond R_previous_current(
        scene.cameraRotation(std::max(0.0, t - 1 / kRate)).transpose() * scene.cameraRotation(t));
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

// Only planes found static may get homography factors: the wall and floor, and the panel while it
// stands still; a rejected panel is not among them.
TEST(PlaneVerifier, PlanesJudgedStaticAreTheStaticOnes) {
  EXPECT_EQ(run(Eigen::Vector3d(0, 0, -1.0)).judgedStatic(), (std::set<int>{kWall, kFloor}));
  EXPECT_EQ(run(Eigen::Vector3d::Zero()).judgedStatic(), (std::set<int>{kWall, kFloor, kPanel}));
  EXPECT_TRUE(run(Eigen::Vector3d::Zero(), false).judgedStatic().empty());
}

TEST(PlaneVerifier, AFrameGivenBeforeTheRejectionIsScreenedAgain) {
  FeatureFrame earlier;
  for (const int plane : {kWall, kFloor, kPanel}) {
    TrackedFeature f;
    f.id = plane;
    f.plane_id = plane;
    earlier.features.push_back(f);
  }
  const auto planes = [](const FeatureFrame& f) {
    std::set<int> out;
    for (const TrackedFeature& x : f.features) out.insert(x.plane_id);
    return out;
  };
  EXPECT_EQ(planes(run(Eigen::Vector3d(0, 0, -1.0)).withoutRejected(earlier)),
            (std::set<int>{kWall, kFloor}));
  EXPECT_EQ(planes(run(Eigen::Vector3d::Zero()).withoutRejected(earlier)),
            (std::set<int>{kWall, kFloor, kPanel}));
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
