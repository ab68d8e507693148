// The camera-height factor: zero at the true height, one unit per sigma, the side of the plane,
// and Jacobians against central differences in the tangent spaces.
#include <gtest/gtest.h>

#include <ceres/sphere_manifold.h>

#include <memory>
#include <random>

#include "mrpt_modules/factors/camera_height_factor.h"
#include "mrpt_modules/factors/pose_manifold.h"
#include "tests/factors/jacobian_check.h"
#include "tests/factors/random_poses.h"

namespace rpvio {
namespace {

using test::poseBlock;
using test::randomPose;

/// A body pose, a mount and a random plane; the camera centre's signed distance to it.
struct Config {
  Eigen::Isometry3d W_b, T_BC;
  Eigen::Vector3d n;
  double d;
  explicit Config(std::mt19937_64& rng) {
    std::normal_distribution<double> g(0, 1);
    W_b = randomPose(rng, 3.0);
    T_BC = randomPose(rng, 0.2);
    n = Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
    d = 2 * g(rng);
  }
  double signedHeight() const { return n.dot((W_b * T_BC).translation()) - d; }
  std::vector<std::vector<double>> blocks() const {
    return {poseBlock(W_b), poseBlock(T_BC), {n.x(), n.y(), n.z()}, {d}};
  }
};

double residual(const ceres::CostFunction& f, const std::vector<std::vector<double>>& x) {
  std::vector<const double*> p;
  for (const auto& b : x) p.push_back(b.data());
  double r;
  f.Evaluate(p.data(), &r, nullptr);
  return r;
}

TEST(CameraHeightFactor, ZeroAtTheHeightOnItsSideAndOnePerSigma) {
  std::mt19937_64 rng(7);
  for (int k = 0; k < 50; ++k) {
    const Config c(rng);
    const double h = std::abs(c.signedHeight()), side = c.signedHeight() > 0 ? 1 : -1;
    const double sigma = 0.05;
    std::unique_ptr<ceres::CostFunction> exact(CameraHeightResidual::create(h, side, 1 / sigma));
    EXPECT_NEAR(residual(*exact, c.blocks()), 0.0, 1e-9);
    // One sigma higher than the camera is: one unit.
    std::unique_ptr<ceres::CostFunction> higher(
        CameraHeightResidual::create(h + sigma, side, 1 / sigma));
    EXPECT_NEAR(residual(*higher, c.blocks()), -1.0, 1e-9);
    // The same distance on the other side of the plane is not the height.
    std::unique_ptr<ceres::CostFunction> other_side(
        CameraHeightResidual::create(h, -side, 1 / sigma));
    EXPECT_NEAR(std::abs(residual(*other_side, c.blocks())), 2 * h / sigma, 1e-6);
  }
}

TEST(CameraHeightFactor, JacobiansMatchCentralDifferencesInTangentSpace) {
  std::mt19937_64 rng(13);
  const PoseManifold pose_manifold;
  const ceres::SphereManifold<3> sphere;
  double worst = 0;
  for (int k = 0; k < 50; ++k) {
    const Config c(rng);
    std::unique_ptr<ceres::CostFunction> f(CameraHeightResidual::create(1.65, 1, 20));
    worst =
        std::max(worst, test::worstJacobianError(
                            *f, c.blocks(), {&pose_manifold, &pose_manifold, &sphere, nullptr}));
  }
  std::printf("camera-height factor: worst relative Jacobian error over 50 configurations %.2e\n",
              worst);
  EXPECT_LT(worst, 1e-6);
}

}  // namespace
}  // namespace rpvio
