// The simulated flight matches the paper's numbers, and its IMU is physically right: integrating
// the noise-free IMU from the true initial state reproduces the true trajectory.
#include <gtest/gtest.h>

#include "sim/flight_trajectory.h"
#include "sim/imu_simulator.h"
#include "sim/sim_config.h"

namespace rpvio::sim {
namespace {

Eigen::Matrix3d expSO3(const Eigen::Vector3d& w) {
  const double angle = w.norm();
  if (angle < 1e-12) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
}

TEST(Flight, PaperNumbers) {
  const FlightTrajectory flight{FlightParams{}};
  double length = 0, max_speed = 0;
  Eigen::Vector3d prev = flight.at(0).p;
  const double dt = 0.005;
  for (double t = dt; t <= 80.0 + 1e-9; t += dt) {
    const FlightState s = flight.at(t);
    length += (s.p - prev).norm();
    prev = s.p;
    max_speed = std::max(max_speed, s.v.norm());
    // The camera (body x) always looks at the circle's centre, within the small tilt.
    const Eigen::Vector3d to_centre = -Eigen::Vector3d(s.p.x(), s.p.y(), 0).normalized();
    EXPECT_GT(s.R_wb.col(0).dot(to_centre), std::cos(0.06));
  }
  EXPECT_NEAR(length, 200.0, 10.0);
  EXPECT_LE(max_speed, 3.0);
  EXPECT_NEAR(flight.at(0).v.norm(), 0.0, 1e-12);  // starts from rest
  EXPECT_GT(flight.at(0).a.z(), 1.0);              // with a vertical push
}

/// The motions of every profile (the hard one flies lower, with a smaller push and wave; the
/// platforms' are the ones of PlatformMotion below).
class BothProfiles : public ::testing::TestWithParam<const char*> {
 protected:
  FlightTrajectory flight{SimConfig::profile(GetParam()).flight};
};
INSTANTIATE_TEST_SUITE_P(Profiles, BothProfiles,
                         ::testing::Values("paper", "hard", "handheld", "drone", "ground-robot",
                                           "car"));

TEST_P(BothProfiles, FlightDerivativesMatchFiniteDifferences) {
  const double h = 1e-5;
  for (double t : {0.3, 7.0, 29.0, 33.3, 79.0}) {  // the car turns from 26 s to 34 s
    const FlightState s = flight.at(t), a = flight.at(t - h), b = flight.at(t + h);
    EXPECT_LT((s.v - (b.p - a.p) / (2 * h)).norm(), 1e-6);
    EXPECT_LT((s.a - (b.v - a.v) / (2 * h)).norm(), 1e-6);
    const Eigen::AngleAxisd d(a.R_wb.transpose() * b.R_wb);
    EXPECT_LT((s.omega_b - d.angle() * d.axis() / (2 * h)).norm(), 1e-6);
  }
}

TEST_P(BothProfiles, NoiseFreeImuIntegrationReproducesGroundTruth) {
  ImuNoise noise;
  const auto imu = simulateImu(flight, noise, {}, 10.0, false, 1);
  const Eigen::Vector3d g(0, 0, -noise.gravity);
  FlightState s0 = flight.at(0);
  Eigen::Matrix3d R = s0.R_wb;
  Eigen::Vector3d p = s0.p, v = s0.v;
  for (size_t k = 0; k + 1 < imu.size(); ++k) {
    const double dt = imu[k + 1].t - imu[k].t;
    // Midpoint rule: rotation by the mean rate, world acceleration averaged over the interval.
    const Eigen::Matrix3d R_next = R * expSO3(0.5 * (imu[k].gyro + imu[k + 1].gyro) * dt);
    const Eigen::Vector3d a = 0.5 * (R * imu[k].accel + R_next * imu[k + 1].accel) + g;
    p += v * dt + 0.5 * a * dt * dt;
    v += a * dt;
    R = R_next;
  }
  const FlightState truth = flight.at(imu.back().t);
  EXPECT_NEAR(imu.back().t, 10.0, 1e-9);
  EXPECT_LT((p - truth.p).norm(), 0.01);
  EXPECT_LT(Eigen::AngleAxisd(R.transpose() * truth.R_wb).angle() * 180 / M_PI, 0.1);
}

/// Peak angular rate and speed range of a profile's motion over 60 s, sampled at 200 Hz.
struct MotionFigures {
  double max_rate = 0, min_speed = 1e9, max_speed = 0, min_z = 1e9, max_z = -1e9;
};
MotionFigures figures(const FlightTrajectory& flight, double from) {
  MotionFigures f;
  for (double t = from; t <= 60; t += 0.005) {
    const FlightState s = flight.at(t);
    f.max_rate = std::max(f.max_rate, s.omega_b.norm());
    f.min_speed = std::min(f.min_speed, s.v.norm());
    f.max_speed = std::max(f.max_speed, s.v.norm());
    f.min_z = std::min(f.min_z, s.p.z());
    f.max_z = std::max(f.max_z, s.p.z());
  }
  return f;
}

TEST(PlatformMotion, HandheldWalksAndTurnsTheHeadAtUpTo3RadPerSecond) {
  const SimConfig c = SimConfig::profile("handheld");
  const MotionFigures f = figures(FlightTrajectory(c.flight), 0);
  EXPECT_NEAR(f.max_rate, 3.0, 0.3);
  EXPECT_NEAR(f.max_speed, 1.4, 0.2);
  EXPECT_NEAR(0.5 * (f.min_z + f.max_z), 1.5, 0.05);
  EXPECT_EQ(c.camera_rate, 30);
  EXPECT_EQ(c.camera.width, 1280);
  EXPECT_EQ(c.camera.hfov_deg, 60);
  EXPECT_EQ(c.flight.start_push, 0);  // no take-off push in any platform profile
}

TEST(PlatformMotion, DroneFlies5MetresPerSecondWithYawTurnsOf2RadPerSecond) {
  const FlightTrajectory flight(SimConfig::profile("drone").flight);
  const MotionFigures f = figures(flight, 5);
  EXPECT_NEAR(f.max_speed, 5.0, 0.1);
  double max_yaw_rate = 0;
  for (double t = 0; t <= 60; t += 0.005) {
    const FlightState s = flight.at(t);
    max_yaw_rate = std::max(max_yaw_rate, std::abs((s.R_wb * s.omega_b).z()));
  }
  EXPECT_NEAR(max_yaw_rate, 2.0, 0.2);
}

TEST(PlatformMotion, GroundRobotIsPlanarAtHalfToOneMetrePerSecondWithSteadyStretches) {
  const SimConfig c = SimConfig::profile("ground-robot");
  const FlightTrajectory flight(c.flight);
  const MotionFigures f = figures(flight, 8);
  EXPECT_GT(f.min_speed, 0.45);
  EXPECT_LT(f.max_speed, 1.05);
  EXPECT_LT(f.max_z - f.min_z, 1e-9);  // planar
  // Near-constant speed (within 2 cm/s over a second) for most of the run.
  int steady = 0, seconds = 0;
  for (double t = 8; t + 1 <= 60; t += 1, ++seconds)
    steady += std::abs(flight.at(t + 1).v.norm() - flight.at(t).v.norm()) < 0.02;
  EXPECT_GT(steady, seconds / 2);
  // Looking ahead: body x along the velocity, within the small tilt.
  const FlightState s = flight.at(30);
  EXPECT_GT(s.R_wb.col(0).dot(s.v.normalized()), std::cos(0.01));
  EXPECT_EQ(c.camera.width, 848);
}

TEST(PlatformMotion, CarReaches10MetresPerSecondAndTurns90DegreesInsideItsYard) {
  const SimConfig c = SimConfig::profile("car");
  const FlightTrajectory flight(c.flight);
  const FlightState start = flight.at(0), end = flight.at(60);
  EXPECT_NEAR(start.v.norm(), 0, 1e-12);
  EXPECT_NEAR(end.v.norm(), 10, 0.1);
  EXPECT_NEAR(Eigen::AngleAxisd(start.R_wb.transpose() * end.R_wb).angle() * 180 / M_PI, 90, 1);
  EXPECT_GT(end.v.y(), 9.9);  // heading +y after the left turn
  for (double t = 0; t <= 60; t += 0.5) {
    const FlightState s = flight.at(t);
    EXPECT_LT(s.p.head<2>().cwiseAbs().maxCoeff(), c.scene.room_half_size - 5) << t;
    EXPECT_NEAR(s.p.z(), 1.6, 1e-12);
  }
  EXPECT_EQ(c.camera_rate, 10);
  EXPECT_EQ(c.camera.width, 1241);
}

TEST(Imu, NoiseHasTheConfiguredDensityAndSeedMatters) {
  const FlightTrajectory flight{FlightParams{}};
  ImuNoise noise;
  const auto clean = simulateImu(flight, noise, {}, 20.0, false, 7);
  const auto a = simulateImu(flight, noise, {}, 20.0, true, 7);
  const auto b = simulateImu(flight, noise, {}, 20.0, true, 7);
  const auto c = simulateImu(flight, noise, {}, 20.0, true, 8);
  double sum_sq = 0;
  for (size_t k = 0; k < clean.size(); ++k) {
    EXPECT_EQ(a[k].gyro, b[k].gyro);
    sum_sq += (a[k].gyro - clean[k].gyro).squaredNorm() / 3;
  }
  EXPECT_NE(a[100].gyro, c[100].gyro);
  // White noise dominates the gyro error over 20 s (bias walk ~1e-4 rad/s).
  const double expected_sigma = noise.gyro_noise_density * std::sqrt(noise.rate_hz);
  EXPECT_NEAR(std::sqrt(sum_sq / clean.size()), expected_sigma, 0.1 * expected_sigma);
}

}  // namespace
}  // namespace rpvio::sim
