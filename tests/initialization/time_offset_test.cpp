// Camera–IMU time offset from an initialization window's rotations (time_offset.h), on the
// simulator's flight and IMU (noise and biases on): the frames carry camera stamps, their
// orientations are the true ones at the IMU-clock times stamp + td, with visual noise.
#include <gtest/gtest.h>

#include <random>

#include "mrpt_modules/initialization/time_offset.h"
#include "sim/simulator.h"

namespace rpvio {
namespace {

struct Window {
  std::vector<double> t;
  std::vector<Eigen::Matrix3d> R;
  std::vector<ImuSample> imu;
};

/// 2 s of frames at 20 Hz from `start`, orientations perturbed by `noise_deg` per axis.
Window window(const sim::Simulator& sim, const std::vector<ImuSample>& stream, double start,
              double td, double noise_deg) {
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0, noise_deg * M_PI / 180);
  Window w;
  for (int k = 0; k <= 40; ++k) {
    const double stamp = start + 0.05 * k;
    w.t.push_back(stamp);
    const Eigen::Vector3d e(noise(rng), noise(rng), noise(rng));
    w.R.push_back(sim.bodyPose(stamp + td).linear() *
                  Eigen::AngleAxisd(e.norm(), e.normalized()).toRotationMatrix());
  }
  // What the estimator holds while initializing: samples up to the last frame's stamp.
  for (const ImuSample& s : stream)
    if (s.t >= start - 0.1 && s.t <= w.t.back()) w.imu.push_back(s);
  return w;
}

/// The simulator and its IMU stream (default sequence; noise on or off).
struct Flight {
  explicit Flight(bool imu_noise)
      : sim([&] {
          sim::SimConfig c;
          c.imu_noise = imu_noise;
          return c;
        }()),
        imu(sim.imuStream()) {}
  sim::Simulator sim;
  std::vector<ImuSample> imu;
};

TEST(TimeOffset, ExactFromANoiseFreeImuAndExactRotations) {
  const Flight flight(false);
  for (double td : {-0.03, 0.0, 0.03}) {
    const Window w = window(flight.sim, flight.imu, 0.4, td, 0);
    const auto e = estimateTimeOffset(w.t, w.R, w.imu, Eigen::Vector3d::Zero(), 0.05);
    ASSERT_TRUE(e) << td;
    EXPECT_NEAR(e->td, td, 2e-4);
    EXPECT_LT(e->gyro_bias.norm(), 1e-5) << e->gyro_bias.transpose();  // no bias without noise
    EXPECT_LT(e->rms_deg, 1e-3);
    // The last frame is left out: its interval moved by +max_offset leaves the samples.
    EXPECT_EQ(e->frames, 40u);
  }
}

TEST(TimeOffset, RecoveredFromTheTakeOffWindowWithNoise) {
  // Gyroscope noise and bias walk as simulated; rotations with 0.005 deg of noise per axis (the
  // estimator's take-off window fits to 0.007 deg rms).
  const Flight flight(true);
  for (double td : {-0.03, 0.0, 0.01, 0.03}) {
    const Window w = window(flight.sim, flight.imu, 0.4, td, 0.005);
    const auto e = estimateTimeOffset(w.t, w.R, w.imu, Eigen::Vector3d::Zero(), 0.05);
    ASSERT_TRUE(e) << td;
    std::printf("td %+.3f s: estimate %+.4f s, sigma %.4f s\n", td, e->td, e->sigma);
    EXPECT_NEAR(e->td, td, 0.0035);
    EXPECT_LT(std::abs(e->td - td), 4 * e->sigma);
    EXPECT_LT(e->sigma, 0.0025);
    EXPECT_LT((e->gyro_bias - flight.sim.config().initial_bias.gyro).norm(), 1e-3);
  }
}

TEST(TimeOffsetDegenerate, ConstantAngularRateDoesNotConstrainTheOffset) {
  // Constant rate about a fixed axis: shifting the times changes no rotation.
  const Eigen::Vector3d w(0.1, -0.2, 0.3);
  std::vector<ImuSample> imu;
  for (int k = 0; k <= 600; ++k) imu.push_back({k * 0.005, w, Eigen::Vector3d::Zero()});
  std::vector<double> t;
  std::vector<Eigen::Matrix3d> R;
  for (int k = 2; k <= 58; ++k) {
    t.push_back(k * 0.05);
    R.push_back(Eigen::AngleAxisd(w.norm() * t.back(), w.normalized()).toRotationMatrix());
  }
  std::string why;
  EXPECT_FALSE(estimateTimeOffset(t, R, imu, Eigen::Vector3d::Zero(), 0.05, &why));
  EXPECT_NE(why.find("do not constrain"), std::string::npos) << why;
  EXPECT_FALSE(estimateTimeOffset({0.5, 0.6, 0.7}, {R[0], R[1], R[2]}, imu, Eigen::Vector3d::Zero(),
                                  0.05, &why));
  EXPECT_NE(why.find("3 frames"), std::string::npos) << why;
}

}  // namespace
}  // namespace rpvio
