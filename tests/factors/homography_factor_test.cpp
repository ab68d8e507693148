// The homography factor on random two-view configurations with a non-trivial camera mount: zero
// on the true geometry, the pixel weighting, and Jacobians against central differences taken in
// the tangent spaces (pose: p + δp, q ⊗ Exp(δθ); normal: ceres::SphereManifold<3>).
#include <gtest/gtest.h>

#include <ceres/sphere_manifold.h>

#include <memory>
#include <random>

#include "mrpt_modules/factors/homography_factor.h"
#include "mrpt_modules/factors/pose_manifold.h"
#include "tests/factors/jacobian_check.h"
#include "tests/factors/random_poses.h"

namespace rpvio {
namespace {

using test::poseBlock;
using test::randomPose;

/// Two camera poses looking at a random plane, a plane point seen by both, and the factor blocks.
struct Config {
  Eigen::Isometry3d T_BC, W_bi, W_bj;
  Eigen::Vector3d n_w, X_w;
  double d_w;

  explicit Config(std::mt19937_64& rng) {
    std::normal_distribution<double> g(0, 1);
    T_BC = randomPose(rng, 0.1);
    W_bi = randomPose(rng, 2.0);
    const Eigen::Isometry3d W_ci = W_bi * T_BC;
    // A point 3-8 m in front of camera i, a plane through it facing camera i.
    X_w = W_ci * (std::uniform_real_distribution<double>(3, 8)(rng) *
                  Eigen::Vector3d(0.3 * g(rng), 0.3 * g(rng), 1));
    n_w = (W_ci.linear() * Eigen::Vector3d(0.4 * g(rng), 0.4 * g(rng), -1)).normalized();
    d_w = n_w.dot(X_w);
    // Camera j: a small motion of camera i that still sees the point.
    Eigen::Isometry3d ci_cj = Eigen::Isometry3d::Identity();
    ci_cj.linear() = Eigen::AngleAxisd(0.2, Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized())
                         .toRotationMatrix();
    ci_cj.translation() = 0.5 * Eigen::Vector3d(g(rng), g(rng), 0.3 * g(rng));
    W_bj = W_ci * ci_cj * T_BC.inverse();
  }
  Eigen::Vector2d observe(const Eigen::Isometry3d& W_b) const {
    const Eigen::Vector3d c = (W_b * T_BC).inverse() * X_w;
    return c.head<2>() / c.z();
  }
  std::vector<std::vector<double>> blocks() const {
    return {poseBlock(W_bi), poseBlock(W_bj), poseBlock(T_BC), {n_w.x(), n_w.y(), n_w.z()}, {d_w}};
  }
};

double residualNorm(const ceres::CostFunction& f, const std::vector<std::vector<double>>& x) {
  std::vector<const double*> p;
  for (const auto& b : x) p.push_back(b.data());
  double r[2];
  f.Evaluate(p.data(), r, nullptr);
  return std::hypot(r[0], r[1]);
}

TEST(HomographyFactorTest, ZeroOnTrueGeometryAndOnePerSigmaPixels) {
  std::mt19937_64 rng(3);
  for (int k = 0; k < 50; ++k) {
    const Config c(rng);
    const double sqrt_info = visionSqrtInfo(460, 1.5);
    std::unique_ptr<ceres::CostFunction> exact(
        HomographyResidual::create(c.observe(c.W_bi), c.observe(c.W_bj), sqrt_info));
    EXPECT_LT(residualNorm(*exact, c.blocks()), 1e-9);
    // An observation 1.5 px (at f = 460) off costs one unit of residual.
    std::unique_ptr<ceres::CostFunction> off(HomographyResidual::create(
        c.observe(c.W_bi), c.observe(c.W_bj) + Eigen::Vector2d(0, 1.5 / 460), sqrt_info));
    EXPECT_NEAR(residualNorm(*off, c.blocks()), 1.0, 1e-9);
  }
}

TEST(HomographyFactorTest, JacobiansMatchCentralDifferencesInTangentSpace) {
  std::mt19937_64 rng(11);
  const PoseManifold pose_manifold;
  const ceres::SphereManifold<3> sphere;
  double worst = 0;
  for (int k = 0; k < 50; ++k) {
    const Config c(rng);
    std::unique_ptr<ceres::CostFunction> f(
        HomographyResidual::create(c.observe(c.W_bi), c.observe(c.W_bj), visionSqrtInfo()));
    // Away from the truth, so that no Jacobian term vanishes with the residual.
    auto x = c.blocks();
    x[1][0] += 0.05;
    x[4][0] *= 1.2;
    const Eigen::Vector3d tilted = (c.n_w + Eigen::Vector3d(0.05, -0.03, 0.04)).normalized();
    x[3] = {tilted.x(), tilted.y(), tilted.z()};
    worst = std::max(
        worst, test::worstJacobianError(
                   *f, x, {&pose_manifold, &pose_manifold, &pose_manifold, &sphere, nullptr}));
  }
  std::printf("homography factor: worst relative Jacobian error over 50 configurations %.2e\n",
              worst);
  EXPECT_LT(worst, 1e-5);
}

TEST(HomographyFactorTest, PlaneInducedHomographyMapsPlanePoints) {
  std::mt19937_64 rng(5);
  const Config c(rng);
  const RigidTransform<double> W_ci{(c.W_bi * c.T_BC).linear(), (c.W_bi * c.T_BC).translation()};
  const RigidTransform<double> W_cj{(c.W_bj * c.T_BC).linear(), (c.W_bj * c.T_BC).translation()};
  const Eigen::Matrix3d H = planeInducedHomography(W_ci, W_cj, c.n_w, c.d_w);
  const Eigen::Vector2d ui = c.observe(c.W_bi), uj = c.observe(c.W_bj);
  const Eigen::Vector3d x = H * ui.homogeneous();
  EXPECT_LT((x.hnormalized() - uj).norm(), 1e-12);
}

}  // namespace
}  // namespace rpvio
