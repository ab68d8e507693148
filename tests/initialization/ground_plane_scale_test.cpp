// The ground plane of an up-to-scale window and gravity's direction from the preintegrations
// (ground_plane_scale.h), on synthetic structure.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "mrpt_modules/initialization/ground_plane_scale.h"

namespace rpvio {
namespace {

/// A camera 0.8 m above a floor (label 1) looking ahead at a wall 6 m away (label 2), in SfM
/// units of 1/scale m, camera r tilted by `pitch` (x right, y down, z ahead); points jittered by
/// 1 mm.
SfmWindow floorAndWall(double scale, double pitch, Eigen::Vector3d* down_r) {
  const Eigen::Matrix3d R_r_level =
      Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitX()).toRotationMatrix();
  *down_r = R_r_level * Eigen::Vector3d::UnitY();
  std::mt19937 rng(3);
  std::normal_distribution<double> jitter(0, 0.001);
  SfmWindow w;
  auto add = [&](int label, const Eigen::Vector3d& level) {
    SfmTrack t;
    t.feature_id = static_cast<int>(w.tracks.size());
    t.plane_id = label;
    t.X_r = R_r_level * (level + Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng))) / scale;
    w.tracks.push_back(t);
  };
  for (int i = 0; i < 30; ++i) {
    add(1, Eigen::Vector3d(-2 + 0.8 * (i % 6), 0.8, 2 + 0.5 * (i / 6)));  // floor, 0.8 m below
    add(2, Eigen::Vector3d(-2 + 0.8 * (i % 6), -1 + 0.4 * (i / 6), 6));   // wall, 6 m ahead
  }
  SfmTrack unlabelled;
  unlabelled.X_r = Eigen::Vector3d(0, 0, 1);
  w.tracks.push_back(unlabelled);
  return w;
}

TEST(GroundPlane, TheFloorIsFoundAtTheCamerasHeightInSfmUnits) {
  Eigen::Vector3d down_r;
  const SfmWindow w = floorAndWall(2.5, 0.2, &down_r);
  const auto ground = findGroundPlane(w, down_r, 10, 20);
  ASSERT_TRUE(ground);
  EXPECT_EQ(ground->plane_id, 1);
  EXPECT_NEAR(ground->d * 2.5, 0.8, 0.002);  // scale = 0.8 m / d
  EXPECT_LT(ground->tilt_deg, 0.5);
  EXPECT_GT(ground->n_r.dot(down_r), 0.99);
}

TEST(GroundPlane, NoneWhenGravityDisagreesOrTooFewPoints) {
  Eigen::Vector3d down_r;
  const SfmWindow w = floorAndWall(1.0, 0.0, &down_r);
  // Gravity 20° off the floor's normal.
  const Eigen::Vector3d off = Eigen::AngleAxisd(0.35, Eigen::Vector3d::UnitZ()) * down_r;
  EXPECT_FALSE(findGroundPlane(w, off, 10, 20));
  EXPECT_FALSE(findGroundPlane(w, down_r, 10, 31));  // 30 floor points
  // The ceiling is level too, but above the camera: its normal points up.
  EXPECT_FALSE(findGroundPlane(w, -down_r, 10, 20));
}

TEST(GroundPlane, GravityFromTheSpecificForceOfABodyAtRest) {
  // A body at rest, tilted: the accelerometer reads R_wbᵀ (0, 0, g) at every sample.
  const Eigen::Matrix3d R_r_b = (Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()) *
                                 Eigen::AngleAxisd(-0.2, Eigen::Vector3d::UnitY()))
                                    .toRotationMatrix();
  const Eigen::Vector3d up_r(0.1, -0.9, 0.2);
  const Eigen::Vector3d accel = R_r_b.transpose() * up_r.normalized() * 9.81;
  std::vector<std::shared_ptr<ImuPreintegration>> imu{nullptr};
  for (int k = 0; k < 5; ++k) {
    auto pre =
        std::make_shared<ImuPreintegration>(accel, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                                            Eigen::Vector3d::Zero(), ImuNoise{});
    for (int j = 0; j < 10; ++j) pre->push(0.005, accel, Eigen::Vector3d::Zero());
    imu.push_back(pre);
  }
  const std::vector<Eigen::Matrix3d> R(6, R_r_b);
  EXPECT_LT((gravityDirection(R, imu) + up_r.normalized()).norm(), 1e-9);
}

}  // namespace
}  // namespace rpvio
