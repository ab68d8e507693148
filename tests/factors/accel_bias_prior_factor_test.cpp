// The accelerometer-bias prior: zero at its bias, one unit per sigma along each axis, blind to the
// velocity and the gyroscope bias, and its Jacobian against central differences.
#include <gtest/gtest.h>

#include <random>

#include "mrpt_modules/factors/accel_bias_prior_factor.h"
#include "tests/factors/jacobian_check.h"

namespace rpvio {
namespace {

Eigen::Vector3d evaluate(const ceres::CostFunction& f, const std::vector<double>& speed_bias) {
  const double* p = speed_bias.data();
  Eigen::Vector3d r;
  f.Evaluate(&p, r.data(), nullptr);
  return r;
}

TEST(AccelBiasPriorFactor, ZeroAtItsBiasOnePerSigmaAndBlindToTheRest) {
  const Eigen::Vector3d bias(0.05, -0.04, 0.06);
  const double sigma = 0.1;
  const AccelBiasPriorResidual f(bias, sigma);
  std::vector<double> x = {3, -1, 0.5, bias.x(), bias.y(), bias.z(), 0.01, 0.02, -0.03};
  EXPECT_LT(evaluate(f, x).norm(), 1e-12);
  for (int axis = 0; axis < 3; ++axis) {
    std::vector<double> moved = x;
    moved[3 + axis] += sigma;
    EXPECT_NEAR(evaluate(f, moved)(axis), 1.0, 1e-12);
    EXPECT_NEAR(evaluate(f, moved).norm(), 1.0, 1e-12);
  }
  for (int other : {0, 1, 2, 6, 7, 8}) {
    std::vector<double> moved = x;
    moved[other] += 1;
    EXPECT_LT(evaluate(f, moved).norm(), 1e-12);
  }
}

TEST(AccelBiasPriorFactor, JacobianMatchesCentralDifferences) {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> g(0, 1);
  double worst = 0;
  for (int k = 0; k < 20; ++k) {
    const AccelBiasPriorResidual f(Eigen::Vector3d(g(rng), g(rng), g(rng)) * 0.1, 0.2);
    std::vector<double> x(9);
    for (double& v : x) v = g(rng);
    worst = std::max(worst, test::worstJacobianError(f, {x}, {nullptr}));
  }
  EXPECT_LT(worst, 1e-8);
}

}  // namespace
}  // namespace rpvio
