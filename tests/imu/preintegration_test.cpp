// IMU preintegration: Jacobians and covariance against numeric differentiation and Monte Carlo,
// on the simulator's flight (exact IMU).
#include <gtest/gtest.h>

#include <random>

#include "mrpt_modules/imu/imu_preintegration.h"
#include "mrpt_modules/imu/so3.h"
#include "sim/flight_trajectory.h"
#include "sim/imu_simulator.h"

namespace rpvio {
namespace {

std::vector<ImuSample> flightImu(double duration) {
  const sim::FlightTrajectory flight{sim::FlightParams{}};
  ImuNoise noise;
  auto all = sim::simulateImu(flight, noise, {}, 3.0 + duration, false, 1);
  return std::vector<ImuSample>(all.begin() + 600,
                                all.begin() + 600 + static_cast<int>(duration * 200) + 1);
}

ImuPreintegration integrate(const std::vector<ImuSample>& s, const Eigen::Vector3d& ba,
                            const Eigen::Vector3d& bg) {
  ImuPreintegration pre(s[0].accel, s[0].gyro, ba, bg, ImuNoise{});
  for (size_t k = 1; k < s.size(); ++k) pre.push(s[k].t - s[k - 1].t, s[k].accel, s[k].gyro);
  return pre;
}

Eigen::Vector3d logQuaternion(const Eigen::Quaterniond& q) {
  const Eigen::AngleAxisd aa(q);
  return aa.angle() * aa.axis();
}

TEST(Preintegration, BiasJacobiansMatchNumericDifferentiation) {
  const auto samples = flightImu(1.0);
  const Eigen::Vector3d ba(0.05, -0.03, 0.02), bg(0.004, -0.002, 0.003);
  const ImuPreintegration pre = integrate(samples, ba, bg);
  const auto& J = pre.jacobian();
  const double eps = 1e-5;
  double worst = 0;
  for (int which = 0; which < 2; ++which)
    for (int axis = 0; axis < 3; ++axis) {
      Eigen::Vector3d d = Eigen::Vector3d::Zero();
      d[axis] = eps;
      const ImuPreintegration plus =
          integrate(samples, which == 0 ? ba + d : ba, which == 1 ? bg + d : bg);
      const ImuPreintegration minus =
          integrate(samples, which == 0 ? ba - d : ba, which == 1 ? bg - d : bg);
      const int col = (which == 0 ? ImuPreintegration::kBa : ImuPreintegration::kBg) + axis;
      const Eigen::Vector3d num_p = (plus.deltaP() - minus.deltaP()) / (2 * eps);
      const Eigen::Vector3d num_v = (plus.deltaV() - minus.deltaV()) / (2 * eps);
      const Eigen::Vector3d num_q = (logQuaternion(pre.deltaQ().inverse() * plus.deltaQ()) -
                                     logQuaternion(pre.deltaQ().inverse() * minus.deltaQ())) /
                                    (2 * eps);
      const Eigen::Vector3d an_p = J.block<3, 1>(ImuPreintegration::kP, col);
      const Eigen::Vector3d an_v = J.block<3, 1>(ImuPreintegration::kV, col);
      const Eigen::Vector3d an_q = J.block<3, 1>(ImuPreintegration::kR, col);
      for (const auto& [num, an] : {std::pair{num_p, an_p}, {num_v, an_v}, {num_q, an_q}}) {
        if (an.norm() < 1e-12 && num.norm() < 1e-9) continue;  // e.g. rotation w.r.t. accel bias
        const double rel = (num - an).norm() / std::max(an.norm(), 1e-3);
        worst = std::max(worst, rel);
        EXPECT_LT(rel, 1e-5) << "bias " << which << " axis " << axis << " analytic "
                             << an.transpose() << " numeric " << num.transpose();
      }
    }
  std::printf("worst relative error of the bias Jacobians: %.2e\n", worst);
}

TEST(Preintegration, CovarianceMatchesMonteCarlo) {
  const auto clean = flightImu(0.5);
  ImuNoise noise;
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  const ImuPreintegration reference = integrate(clean, zero, zero);
  std::mt19937_64 rng(42);
  std::normal_distribution<double> n01;
  const double dt = 1.0 / noise.rate_hz;
  const double sa = noise.accel_noise_density / std::sqrt(dt),
               sg = noise.gyro_noise_density / std::sqrt(dt);
  const int runs = 2000;
  Eigen::Matrix<double, 9, 9> sample_cov = Eigen::Matrix<double, 9, 9>::Zero();
  for (int r = 0; r < runs; ++r) {
    // White noise on every sample and biases drifting as random walks from zero, as simulated.
    std::vector<ImuSample> noisy = clean;
    Eigen::Vector3d ba = Eigen::Vector3d::Zero(), bg = Eigen::Vector3d::Zero();
    for (auto& s : noisy) {
      s.accel += ba + sa * Eigen::Vector3d(n01(rng), n01(rng), n01(rng));
      s.gyro += bg + sg * Eigen::Vector3d(n01(rng), n01(rng), n01(rng));
      ba += noise.accel_random_walk * std::sqrt(dt) * Eigen::Vector3d(n01(rng), n01(rng), n01(rng));
      bg += noise.gyro_random_walk * std::sqrt(dt) * Eigen::Vector3d(n01(rng), n01(rng), n01(rng));
    }
    const ImuPreintegration p = integrate(noisy, zero, zero);
    Eigen::Matrix<double, 9, 1> e;
    e << p.deltaP() - reference.deltaP(), logQuaternion(reference.deltaQ().inverse() * p.deltaQ()),
        p.deltaV() - reference.deltaV();
    sample_cov += e * e.transpose() / runs;
  }
  const Eigen::Matrix<double, 9, 9> predicted = reference.covariance().topLeftCorner<9, 9>();
  for (int i = 0; i < 9; ++i) {
    const double ratio = predicted(i, i) / sample_cov(i, i);
    std::printf("state %d: predicted/Monte-Carlo variance %.3f (%.3g / %.3g)\n", i, ratio,
                predicted(i, i), sample_cov(i, i));
    EXPECT_NEAR(ratio, 1.0, 0.1) << "state " << i;  // 2000 runs: 3% standard error
  }
}

TEST(Preintegration, ResidualVanishesOnTheTrueTrajectory) {
  const sim::FlightTrajectory flight{sim::FlightParams{}};
  const auto samples = flightImu(1.0);
  const ImuPreintegration pre =
      integrate(samples, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  const auto a = flight.at(samples.front().t), b = flight.at(samples.back().t);
  const Eigen::Vector3d z = Eigen::Vector3d::Zero();
  const auto r = pre.evaluate(a.p, Eigen::Quaterniond(a.R_wb), a.v, z, z, b.p,
                              Eigen::Quaterniond(b.R_wb), b.v, z, z, Eigen::Vector3d(0, 0, -9.81));
  EXPECT_LT(r.segment<3>(0).norm(), 2e-3);  // midpoint integration error over 1 s
  EXPECT_LT(r.segment<3>(3).norm(), 1e-5);
  EXPECT_LT(r.segment<3>(6).norm(), 2e-3);
}

TEST(Preintegration, RepropagateEqualsFreshIntegration) {
  const auto samples = flightImu(0.5);
  ImuPreintegration pre = integrate(samples, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  const Eigen::Vector3d ba(0.1, 0.2, -0.1), bg(0.01, -0.02, 0.005);
  pre.repropagate(ba, bg);
  const ImuPreintegration fresh = integrate(samples, ba, bg);
  EXPECT_LT((pre.deltaP() - fresh.deltaP()).norm(), 1e-12);
  EXPECT_LT(pre.deltaQ().angularDistance(fresh.deltaQ()), 1e-12);
  EXPECT_LT((pre.covariance() - fresh.covariance()).norm(), 1e-15);
}

}  // namespace
}  // namespace rpvio
