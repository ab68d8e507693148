// Visual-inertial alignment on the simulator: camera trajectory from the ground truth scaled by an
// unknown factor, noisy IMU with biases; recover scale, gravity, gyro bias and velocities.
#include <gtest/gtest.h>

#include "mrpt_modules/initialization/visual_inertial_alignment.h"
#include "sim/simulator.h"

namespace rpvio {
namespace {

TEST(VisualInertialAlignment, RecoversScaleGravityBiasAndVelocity) {
  sim::SimConfig config;
  config.duration = 3.0;
  sim::Simulator sim(config);
  const auto imu = sim.imuStream();
  const double unknown_scale = 0.37;
  const Eigen::Isometry3d T_w_c0 = sim.cameraPose(0.0);
  std::vector<UpToScaleFrame> frames;
  const int step = 10;  // a frame every 50 ms, 2 s of window
  for (size_t k = 0; k + step < imu.size() && frames.size() < 41; k += step) {
    UpToScaleFrame f;
    const Eigen::Isometry3d T_c0_c = T_w_c0.inverse() * sim.cameraPose(imu[k].t);
    f.R_c0_c = T_c0_c.linear();
    f.p_c0_c = unknown_scale * T_c0_c.translation();
    if (k > 0) {
      f.from_previous = std::make_shared<ImuPreintegration>(imu[k - step].accel, imu[k - step].gyro,
                                                            Eigen::Vector3d::Zero(),
                                                            Eigen::Vector3d::Zero(), config.imu);
      for (size_t j = k - step + 1; j <= k; ++j)
        f.from_previous->push(imu[j].t - imu[j - 1].t, imu[j].accel, imu[j].gyro);
    }
    frames.push_back(f);
  }
  std::string why;
  const auto result = alignVisualInertial(frames, config.camera.T_BC(), 9.81, &why);
  ASSERT_TRUE(result) << why;
  const double scale_error = std::abs(result->scale * unknown_scale - 1.0);
  const Eigen::Vector3d g_true_c0 = T_w_c0.linear().transpose() * Eigen::Vector3d(0, 0, -9.81);
  const double gravity_error_deg =
      std::acos(
          std::clamp(result->gravity_c0.normalized().dot(g_true_c0.normalized()), -1.0, 1.0)) *
      180 / M_PI;
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

TEST(VisualInertialAlignment, TooFewFramesSaysWhy) {
  std::vector<UpToScaleFrame> frames(2);
  std::string why;
  EXPECT_FALSE(alignVisualInertial(frames, Eigen::Isometry3d::Identity(), 9.81, &why));
  EXPECT_NE(why.find("too few frames"), std::string::npos);
}

}  // namespace
}  // namespace rpvio
