// The IMU link between two window frames: its prediction against constant-acceleration motion,
// gaps and saturation found in the samples, and the noise inflated for them.
#include <gtest/gtest.h>

#include <cmath>

#include "mrpt_modules/imu/imu_link.h"

namespace rpvio {
namespace {

constexpr double kGravity = 9.81;

/// Samples at `rate_hz` over [t0, t1] of a body that does not rotate and accelerates by `a` in
/// the world (specific force a - g).
std::vector<ImuSample> constantAcceleration(const Eigen::Vector3d& a, double t0, double t1,
                                            double rate_hz = 200) {
  std::vector<ImuSample> samples;
  for (int k = 0; t0 + k / rate_hz <= t1 + 1e-12; ++k) {
    ImuSample s;
    s.t = t0 + k / rate_hz;
    s.accel = a + Eigen::Vector3d(0, 0, kGravity);
    samples.push_back(s);
  }
  return samples;
}

TEST(ImuLink, PredictsConstantAccelerationExactly) {
  const ImuLink link(ImuNoise{}, kGravity, ImuLinkOptions{});
  const Eigen::Vector3d a(0.4, -0.2, 0.3), v0(1.0, 2.0, -0.5), p0(3, 4, 5);
  const auto samples = constantAcceleration(a, 10.0, 11.0);
  const double speed_bias[9] = {v0.x(), v0.y(), v0.z(), 0, 0, 0, 0, 0, 0};
  const double pose[7] = {p0.x(), p0.y(), p0.z(), 0, 0, 0, 1};
  const auto pre = link.preintegrate(samples, 10.0, 11.0, speed_bias);
  ASSERT_TRUE(pre);
  EXPECT_NEAR(pre->sumDt(), 1.0, 1e-12);
  double predicted_pose[7], predicted_speed_bias[9];
  link.predict(pose, speed_bias, *pre, predicted_pose, predicted_speed_bias);
  const Eigen::Vector3d p = p0 + v0 + 0.5 * a, v = v0 + a;  // T = 1 s
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(predicted_pose[i], p[i], 1e-9);
    EXPECT_NEAR(predicted_speed_bias[i], v[i], 1e-9);
  }
  EXPECT_NEAR(predicted_pose[6], 1.0, 1e-12);  // no rotation
}

TEST(ImuLink, FindsGapsAndSaturation) {
  const ImuLink link(ImuNoise{}, kGravity, ImuLinkOptions{});
  auto samples = constantAcceleration(Eigen::Vector3d(0.1, 0, 0), 0.0, 0.5);
  EXPECT_FALSE(link.defects(samples, 0.0, 0.5).any());
  EXPECT_TRUE(link.defects({}, 0.0, 0.5).gap);
  // The samples end 0.1 s before t1: a gap (longer than max_step_s, 0.05 s).
  EXPECT_TRUE(link.defects(samples, 0.0, 0.6).gap);
  // 0.1 s missing in the middle.
  auto holed = samples;
  holed.erase(holed.begin() + 40, holed.begin() + 60);
  const ImuDefects hole = link.defects(holed, 0.0, 0.5);
  EXPECT_TRUE(hole.gap);
  EXPECT_FALSE(hole.accel_saturated || hole.gyro_saturated);
  // An accelerometer axis stuck at 16 m/s² for three samples.
  for (int k = 50; k < 53; ++k) samples[k].accel.y() = 16.0;
  const ImuDefects stuck = link.defects(samples, 0.0, 0.5);
  EXPECT_TRUE(stuck.accel_saturated);
  EXPECT_FALSE(stuck.gap || stuck.gyro_saturated);
  // Twice the same value is not saturation; nor is a small value repeated (a sensor at rest).
  samples[52].accel.y() = 15.0;
  EXPECT_FALSE(link.defects(samples, 0.0, 0.5).accel_saturated);
  for (int k = 100; k < 103; ++k) samples[k].gyro.z() = 0.01;
  EXPECT_FALSE(link.defects(samples, 0.0, 0.5).gyro_saturated);
}

TEST(ImuLink, AGapInflatesTheWhiteNoise) {
  ImuLinkOptions options;
  options.gap_noise_inflation = 30;
  const ImuLink link(ImuNoise{}, kGravity, options);
  const double speed_bias[9] = {};
  const auto samples = constantAcceleration(Eigen::Vector3d(0.1, 0, 0), 0.0, 0.5);
  auto holed = samples;
  holed.erase(holed.begin() + 40, holed.begin() + 60);
  const auto clean = link.preintegrate(samples, 0.0, 0.5, speed_bias);
  const auto gap = link.preintegrate(holed, 0.0, 0.5, speed_bias);
  ASSERT_TRUE(clean && gap);
  // Velocity and rotation variances grow with the white-noise densities squared (30² = 900).
  const double velocity_ratio = gap->covariance()(ImuPreintegration::kV, ImuPreintegration::kV) /
                                clean->covariance()(ImuPreintegration::kV, ImuPreintegration::kV);
  EXPECT_GT(velocity_ratio, 500);
  EXPECT_LT(velocity_ratio, 1000);
  EXPECT_EQ(link.preintegrate({}, 0.0, 0.5, speed_bias), nullptr);
  EXPECT_EQ(link.preintegrate(samples, 0.5, 0.5, speed_bias), nullptr);
}

}  // namespace
}  // namespace rpvio
