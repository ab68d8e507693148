// IMU factor Jacobians against central differences on the manifolds.
#include <gtest/gtest.h>

#include <memory>

#include "mrpt_modules/factors/imu_factor.h"
#include "mrpt_modules/factors/pose_manifold.h"
#include "sim/imu_simulator.h"
#include "tests/factors/jacobian_check.h"

namespace rpvio {
namespace {

std::vector<double> poseBlock(const Eigen::Vector3d& p, const Eigen::Quaterniond& q) {
  return {p.x(), p.y(), p.z(), q.x(), q.y(), q.z(), q.w()};
}

TEST(ImuFactor, JacobiansMatchNumericDifferentiation) {
  const sim::FlightTrajectory flight{sim::FlightParams{}};
  const auto imu = sim::simulateImu(flight, ImuNoise{}, {}, 6.0, false, 1);
  const size_t i = 1000, j = 1100;  // 0.5 s apart
  auto pre = std::make_shared<ImuPreintegration>(imu[i].accel, imu[i].gyro,
                                                 Eigen::Vector3d(0.02, -0.01, 0.03),
                                                 Eigen::Vector3d(0.001, 0.002, -0.001), ImuNoise{});
  for (size_t k = i + 1; k <= j; ++k) pre->push(imu[k].t - imu[k - 1].t, imu[k].accel, imu[k].gyro);
  const ImuFactor factor(pre, Eigen::Vector3d(0, 0, -9.81));
  const auto a = flight.at(imu[i].t), b = flight.at(imu[j].t);
  // States near the truth, off by a little everywhere, biases away from the linearization point.
  const Eigen::Quaterniond qi =
      Eigen::Quaterniond(a.R_wb) * Eigen::Quaterniond(0.999, 0.02, -0.01, 0.03).normalized();
  const Eigen::Quaterniond qj =
      Eigen::Quaterniond(b.R_wb) * Eigen::Quaterniond(0.998, -0.03, 0.02, 0.01).normalized();
  std::vector<std::vector<double>> x = {
      poseBlock(a.p + Eigen::Vector3d(0.1, -0.2, 0.05), qi),
      {a.v.x() + 0.1, a.v.y(), a.v.z() - 0.1, 0.03, -0.02, 0.01, 0.004, 0.001, -0.003},
      poseBlock(b.p + Eigen::Vector3d(-0.1, 0.1, 0.2), qj),
      {b.v.x(), b.v.y() + 0.2, b.v.z(), 0.01, 0.0, 0.02, 0.002, 0.002, -0.002}};
  const PoseManifold pose_manifold;
  const double worst =
      test::worstJacobianError(factor, x, {&pose_manifold, nullptr, &pose_manifold, nullptr});
  std::printf("IMU factor: worst Jacobian error %.2e\n", worst);
  EXPECT_LT(worst, 1e-5);
}

TEST(PoseManifold, PlusMinusRoundTrip) {
  const PoseManifold m;
  const auto x = poseBlock({1, 2, 3}, Eigen::Quaterniond(0.9, 0.1, -0.3, 0.2).normalized());
  const double delta[6] = {0.1, -0.2, 0.3, 0.05, -0.02, 0.01};
  double y[7], back[6];
  m.Plus(x.data(), delta, y);
  m.Minus(y, x.data(), back);
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(back[k], delta[k], 1e-12);
}

}  // namespace
}  // namespace rpvio
