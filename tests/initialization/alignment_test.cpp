// Visual-inertial alignment on the simulator: camera trajectory from the ground truth scaled by an
// unknown factor, noisy IMU with biases; recover scale, gravity, gyro bias and velocities.
#include <gtest/gtest.h>

#include "mrpt_modules/initialization/visual_inertial_alignment.h"
#include "sim/simulator.h"

namespace rpvio {
namespace {

/// 2 s of frames every 50 ms from `start_s` on: camera poses in c0 from the ground truth, positions
/// times `unknown_scale`, and the preintegrations of the simulator's noisy IMU between them.
std::vector<UpToScaleFrame> windowFrames(const sim::Simulator& sim,
                                         const std::vector<ImuSample>& imu, double unknown_scale,
                                         double start_s = 0) {
  const size_t first = std::lower_bound(imu.begin(), imu.end(), start_s - 1e-9,
                                        [](const ImuSample& s, double t) { return s.t < t; }) -
                       imu.begin();
  const Eigen::Isometry3d T_w_c0 = sim.cameraPose(imu[first].t);
  std::vector<UpToScaleFrame> frames;
  const int step = 10;
  for (size_t k = first; k + step < imu.size() && frames.size() < 41; k += step) {
    UpToScaleFrame f;
    const Eigen::Isometry3d T_c0_c = T_w_c0.inverse() * sim.cameraPose(imu[k].t);
    f.R_c0_c = T_c0_c.linear();
    f.p_c0_c = unknown_scale * T_c0_c.translation();
    if (k > first) {
      f.from_previous = std::make_shared<ImuPreintegration>(
          imu[k - step].accel, imu[k - step].gyro, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
          sim.config().imu);
      for (size_t j = k - step + 1; j <= k; ++j)
        f.from_previous->push(imu[j].t - imu[j - 1].t, imu[j].accel, imu[j].gyro);
    }
    frames.push_back(f);
  }
  return frames;
}

double angleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180 / M_PI;
}

TEST(VisualInertialAlignment, RecoversScaleGravityBiasAndVelocity) {
  sim::SimConfig config;
  config.duration = 3.0;
  sim::Simulator sim(config);
  const auto imu = sim.imuStream();
  const double unknown_scale = 0.37;
  const Eigen::Isometry3d T_w_c0 = sim.cameraPose(0.0);
  const int step = 10;
  std::vector<UpToScaleFrame> frames = windowFrames(sim, imu, unknown_scale);
  std::string why;
  const auto result = alignVisualInertial(frames, config.camera.T_BC(), 9.81, &why);
  ASSERT_TRUE(result) << why;
  const double scale_error = std::abs(result->scale * unknown_scale - 1.0);
  const Eigen::Vector3d g_true_c0 = T_w_c0.linear().transpose() * Eigen::Vector3d(0, 0, -9.81);
  const double gravity_error_deg = angleDeg(result->gravity_c0, g_true_c0);
  const Eigen::Vector3d bg_true = config.initial_bias.gyro;
  const double bias_error = (result->gyro_bias - bg_true).norm() / bg_true.norm();
  const Eigen::Vector3d v_true_c0 = T_w_c0.linear().transpose() * sim.state(imu[20 * step].t).v;
  std::printf(
      "alignment: scale error %.2f%%, gravity direction error %.3f deg, gyro bias error "
      "%.1f%%, velocity error %.3f m/s\n",
      100 * scale_error, gravity_error_deg, 100 * bias_error,
      (result->velocity_c0[20] - v_true_c0).norm());
  EXPECT_LT(scale_error, 0.03);
  EXPECT_LT(gravity_error_deg, 0.5);
  EXPECT_LT(bias_error, 0.2);
  EXPECT_LT((result->velocity_c0[20] - v_true_c0).norm(), 0.05);
}

TEST(VisualInertialAlignment, AKnownScaleAlignsWhereTheAccelerationsDoNotTellIt) {
  // The ground robot's start: planar, from rest to 0.75 m/s, no push. The free alignment cannot
  // pin the scale down; given it (as the camera's height over the ground gives it), gravity and
  // velocity come out right.
  sim::SimConfig config = sim::SimConfig::profile("ground-robot");
  config.duration = 3.0;
  sim::Simulator sim(config);
  const auto imu = sim.imuStream();
  const double unknown_scale = 0.37;
  const Eigen::Isometry3d T_w_c0 = sim.cameraPose(0.0);
  std::vector<UpToScaleFrame> free_frames = windowFrames(sim, imu, unknown_scale);
  std::vector<UpToScaleFrame> known_frames = windowFrames(sim, imu, unknown_scale);
  std::string why;
  const auto free = alignVisualInertial(free_frames, config.camera.T_BC(), 9.81, &why);
  const auto known =
      alignVisualInertial(known_frames, config.camera.T_BC(), 9.81, &why, 1 / unknown_scale);
  ASSERT_TRUE(known) << why;
  if (free)
    std::printf("free alignment: scale %.3f (true %.3f), sigma %.1f%%\n", free->scale,
                1 / unknown_scale, 100 * free->scale_sigma / free->scale);
  EXPECT_TRUE(!free || free->scale_sigma > 0.03 * free->scale);  // what the initializer refuses
  EXPECT_EQ(known->scale, 1 / unknown_scale);
  EXPECT_EQ(known->scale_sigma, 0);
  const Eigen::Vector3d g_true_c0 = T_w_c0.linear().transpose() * Eigen::Vector3d(0, 0, -9.81);
  EXPECT_LT(angleDeg(known->gravity_c0, g_true_c0), 0.5);
  const Eigen::Vector3d v_true_c0 = T_w_c0.linear().transpose() * sim.state(2.0).v;
  EXPECT_LT((known->velocity_c0[40] - v_true_c0).norm(), 0.05);
}

TEST(VisualInertialAlignment, AKnownFirstVelocityAlignsWhereTheAccelerationsDoNotTellIt) {
  // The ground robot at cruise (8-10 s: planar, near-constant velocity): the free alignment cannot
  // pin the scale down. The first frame's velocity, known to 0.02 m/s (the IMU's dead reckoning
  // from the state before a reset), gives it.
  sim::SimConfig config = sim::SimConfig::profile("ground-robot");
  config.duration = 11.0;
  sim::Simulator sim(config);
  const auto imu = sim.imuStream();
  const double unknown_scale = 0.37, start = 8.0;
  std::vector<UpToScaleFrame> free_frames = windowFrames(sim, imu, unknown_scale, start);
  std::vector<UpToScaleFrame> known_frames = windowFrames(sim, imu, unknown_scale, start);
  const Eigen::Isometry3d T_w_c0 = sim.cameraPose(start);
  const Eigen::Vector3d v_true_c0 = T_w_c0.linear().transpose() * sim.state(start).v;
  const Eigen::Vector3d v0 = v_true_c0 + Eigen::Vector3d(0.02, 0, 0);
  std::string why;
  const auto free = alignVisualInertial(free_frames, config.camera.T_BC(), 9.81, &why);
  const auto known = alignVisualInertial(known_frames, config.camera.T_BC(), 9.81, &why, {}, v0);
  ASSERT_TRUE(known) << why;
  if (free)
    std::printf("free alignment: scale %.3f (true %.3f), sigma %.1f%%\n", free->scale,
                1 / unknown_scale, 100 * free->scale_sigma / free->scale);
  std::printf("known first velocity: scale %.4f (true %.4f), sigma %.2f%%\n", known->scale,
              1 / unknown_scale, 100 * known->scale_sigma / known->scale);
  EXPECT_TRUE(!free || free->scale_sigma > 0.03 * free->scale);  // what the initializer refuses
  EXPECT_LT(std::abs(known->scale * unknown_scale - 1), 0.03);
  EXPECT_LT(known->scale_sigma, 0.03 * known->scale);
  const Eigen::Vector3d g_true_c0 = T_w_c0.linear().transpose() * Eigen::Vector3d(0, 0, -9.81);
  EXPECT_LT(angleDeg(known->gravity_c0, g_true_c0), 0.5);
  const Eigen::Vector3d v_end_c0 = T_w_c0.linear().transpose() * sim.state(start + 2.0).v;
  EXPECT_LT((known->velocity_c0[40] - v_end_c0).norm(), 0.05);
}

TEST(VisualInertialAlignment, TooFewFramesSaysWhy) {
  std::vector<UpToScaleFrame> frames(2);
  std::string why;
  EXPECT_FALSE(alignVisualInertial(frames, Eigen::Isometry3d::Identity(), 9.81, &why));
  EXPECT_NE(why.find("too few frames"), std::string::npos);
}

}  // namespace
}  // namespace rpvio
