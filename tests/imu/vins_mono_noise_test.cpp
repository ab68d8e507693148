// imuNoiseFromVinsMono: the densities it gives make this program's preintegration covariance what
// VINS-Mono's midpoint propagation computes from the configuration's figures.
#include <gtest/gtest.h>

#include "mrpt_modules/imu/imu_preintegration.h"
#include "rawlog_io/calibration.h"

namespace rpvio {
namespace {

// VINS-Mono, per step of dt at rest and without rotation: the velocity gains (dt/2)² acc_n² from
// each of the step's two accelerometer samples, the biases dt² acc_w² and dt² gyr_w², the rotation
// (dt/2)² gyr_n² from each gyroscope sample.
TEST(VinsMonoNoise, PreintegrationCovarianceMatchesVinsMonosPropagation) {
  const double rate = 200, dt = 1 / rate, acc_n = 0.08, gyr_n = 0.004, acc_w = 4e-4, gyr_w = 2e-5;
  const ImuNoise noise = imuNoiseFromVinsMono(acc_n, gyr_n, acc_w, gyr_w, rate, 9.81);
  EXPECT_EQ(noise.rate_hz, rate);
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  ImuPreintegration pre(zero, zero, zero, zero, noise);  // free fall: no coupling with rotation
  const int steps = 20;
  for (int k = 0; k < steps; ++k) pre.push(dt, zero, zero);
  const auto& P = pre.covariance();
  using I = ImuPreintegration;
  EXPECT_NEAR(P(I::kBa, I::kBa) / (steps * dt * dt * acc_w * acc_w), 1, 1e-9);
  EXPECT_NEAR(P(I::kBg, I::kBg) / (steps * dt * dt * gyr_w * gyr_w), 1, 1e-9);
  EXPECT_NEAR(P(I::kR, I::kR) / (steps * 2 * 0.25 * dt * dt * gyr_n * gyr_n), 1, 1e-6);
  // The velocity also collects the accelerometer bias's walk through -dt per step: a few per mille.
  EXPECT_NEAR(P(I::kV, I::kV) / (steps * 2 * 0.25 * dt * dt * acc_n * acc_n), 1, 0.01);
}

}  // namespace
}  // namespace rpvio
