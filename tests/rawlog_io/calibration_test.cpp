// calib.ini save/load round trip for both distortion models.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "rawlog_io/calibration.h"
#include "tests/test_util.h"

namespace rpvio {
namespace {

Calibration sample(DistortionModel model) {
  Calibration c;
  c.camera = {752, 480, 458.654, 457.296, 367.215, 248.375, model, {-0.28, 0.074, 1.9e-4, 1.7e-5}};
  c.T_BC.linear() = Eigen::Quaterniond(0.7, 0.1, -0.3, 0.2).normalized().toRotationMatrix();
  c.T_BC.translation() = Eigen::Vector3d(-0.0216, -0.0647, 0.0098);
  c.time_offset = 0.03;
  c.imu = {1.6968e-4, 2.0e-3, 1.9393e-5, 3.0e-3, 200, 9.81};
  return c;
}

TEST(Calibration, RoundTripsBothDistortionModels) {
  for (auto model :
       {DistortionModel::RadTan, DistortionModel::Equidistant, DistortionModel::None}) {
    test::TempDir dir;
    const Calibration a = sample(model);
    saveCalibration(dir.file("calib.ini"), a);
    const Calibration b = loadCalibration(dir.file("calib.ini"));
    EXPECT_EQ(b.camera.model, model);
    EXPECT_EQ(b.camera.width, 752);
    EXPECT_DOUBLE_EQ(b.camera.fy, a.camera.fy);
    if (model != DistortionModel::None) {
      for (int i = 0; i < 4; ++i) EXPECT_DOUBLE_EQ(b.camera.distortion[i], a.camera.distortion[i]);
    }
    EXPECT_TRUE(b.T_BC.isApprox(a.T_BC, 1e-15));
    EXPECT_DOUBLE_EQ(b.time_offset, 0.03);
    EXPECT_DOUBLE_EQ(b.imu.gyro_random_walk, a.imu.gyro_random_walk);
    EXPECT_DOUBLE_EQ(b.imu.gravity, 9.81);
  }
}

TEST(Calibration, MissingKeyIsNamed) {
  test::TempDir dir;
  test::writeText(dir.file("c.ini"), "[camera]\nwidth = 10\n");
  try {
    loadCalibration(dir.file("c.ini"));
    FAIL();
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("missing key 'height'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rpvio

namespace rpvio {
namespace {

// The densities of imuNoiseFromDiscrete describe the same sensor as the discrete figures: white
// noise of σ_d per sample at rate r averages over 1 s to σ_d / √r = σ_c, and a bias whose
// increments have σ_w per sample wanders by σ_w √r = σ_rw in 1 s.
TEST(Calibration, DiscreteImuFiguresBecomeDensitiesOfTheSameSensor) {
  const double rate = 200, acc_n = 0.08, acc_w = 4e-4;
  const ImuNoise noise = imuNoiseFromDiscrete(acc_n, 0.004, acc_w, 2e-5, rate, 9.81);
  std::mt19937 rng(7);
  std::normal_distribution<double> white(0, acc_n), walk(0, acc_w);
  const int seconds = 4000;
  double sum_sq_mean = 0, sum_sq_drift = 0;
  for (int s = 0; s < seconds; ++s) {
    double sum = 0, bias = 0;
    for (int k = 0; k < rate; ++k) {
      sum += white(rng);
      bias += walk(rng);
    }
    sum_sq_mean += std::pow(sum / rate, 2);
    sum_sq_drift += bias * bias;
  }
  // 4000 draws: the sample standard deviation is within 3 % of the true one (2.7 sigma).
  EXPECT_NEAR(std::sqrt(sum_sq_mean / seconds) / noise.accel_noise_density, 1, 0.03);
  EXPECT_NEAR(std::sqrt(sum_sq_drift / seconds) / noise.accel_random_walk, 1, 0.03);
  EXPECT_DOUBLE_EQ(noise.gyro_noise_density, 0.004 / std::sqrt(rate));
  EXPECT_DOUBLE_EQ(noise.gyro_random_walk, 2e-5 * std::sqrt(rate));
  EXPECT_EQ(noise.rate_hz, rate);
}

}  // namespace
}  // namespace rpvio
