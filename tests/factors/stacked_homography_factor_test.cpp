// The stacked homography factor (one block per plane and frame pair) against one
// HomographyResidual per feature: the same residuals and Jacobians (those against central
// differences) without a loss; with a Cauchy loss inside, the same cost, gradient, Gauss–Newton
// matrix and solution as the per-feature blocks with the loss given to Ceres, outliers included.
#include <gtest/gtest.h>

#include <ceres/ceres.h>
#include <ceres/sphere_manifold.h>

#include <memory>
#include <random>

#include "mrpt_modules/factors/homography_factor.h"
#include "mrpt_modules/factors/pose_manifold.h"
#include "mrpt_modules/factors/stacked_homography_factor.h"
#include "tests/factors/jacobian_check.h"
#include "tests/factors/random_poses.h"

namespace rpvio {
namespace {

using test::poseBlock;
using test::randomPose;

/// Two body poses, a mount, a plane facing camera i, and features of it seen by both: every
/// fourth one 8-30 px off in frame j (the outliers a Cauchy loss is for), all 1 px noisy.
struct PlaneScene {
  Eigen::Isometry3d T_BC, W_bi, W_bj;
  Eigen::Vector3d n_w;
  double d_w;
  std::vector<StackedHomographyResiduals::Feature> features;

  PlaneScene(std::mt19937_64& rng, int count) {
    std::normal_distribution<double> g(0, 1);
    T_BC = randomPose(rng, 0.1);
    W_bi = randomPose(rng, 2.0);
    const Eigen::Isometry3d W_ci = W_bi * T_BC;
    const double depth = std::uniform_real_distribution<double>(3, 8)(rng);
    n_w = (W_ci.linear() * Eigen::Vector3d(0.4 * g(rng), 0.4 * g(rng), -1)).normalized();
    d_w = n_w.dot(W_ci * Eigen::Vector3d(0, 0, depth));
    Eigen::Isometry3d ci_cj = Eigen::Isometry3d::Identity();
    ci_cj.linear() = Eigen::AngleAxisd(0.2, Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized())
                         .toRotationMatrix();
    ci_cj.translation() = 0.5 * Eigen::Vector3d(g(rng), g(rng), 0.3 * g(rng));
    W_bj = W_ci * ci_cj * T_BC.inverse();
    const Eigen::Isometry3d W_cj = W_bj * T_BC;
    for (int k = 0; k < count; ++k) {
      // The ray of u_i meets the plane at X_w.
      const Eigen::Vector3d ray = W_ci.linear() * Eigen::Vector3d(0.3 * g(rng), 0.3 * g(rng), 1);
      const Eigen::Vector3d X_w =
          W_ci.translation() + ray * (d_w - n_w.dot(W_ci.translation())) / n_w.dot(ray);
      const Eigen::Vector3d c_i = W_ci.inverse() * X_w, c_j = W_cj.inverse() * X_w;
      const double noise = 1.0 / 460, outlier = (k % 4 == 3) ? (8 + 22 * (k % 7) / 6.0) / 460 : 0;
      features.push_back({c_i.hnormalized(), c_j.hnormalized() +
                                                 noise * Eigen::Vector2d(g(rng), g(rng)) +
                                                 Eigen::Vector2d(outlier, -0.5 * outlier)});
    }
  }
  std::vector<std::vector<double>> blocks() const {
    return {poseBlock(W_bi), poseBlock(W_bj), poseBlock(T_BC), {n_w.x(), n_w.y(), n_w.z()}, {d_w}};
  }
};

TEST(StackedHomographyFactorTest, WithoutLossItsRowsAreThePerFeatureFactorsWithTheirJacobians) {
  std::mt19937_64 rng(21);
  const PoseManifold pose_manifold;
  const ceres::SphereManifold<3> sphere;
  double worst = 0, worst_row = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const PlaneScene scene(rng, 6);
    const StackedHomographyResiduals stacked(scene.features, visionSqrtInfo(), nullptr);
    ASSERT_EQ(stacked.num_residuals(), 12);
    auto x = scene.blocks();
    x[1][0] += 0.05;  // away from the truth, so that no Jacobian term vanishes with the residual
    x[4][0] *= 1.2;
    std::vector<const double*> p;
    for (const auto& b : x) p.push_back(b.data());
    std::vector<double> rows(12);
    ASSERT_TRUE(stacked.Evaluate(p.data(), rows.data(), nullptr));
    for (size_t f = 0; f < scene.features.size(); ++f) {
      const HomographyResidual single(scene.features[f].u_i, scene.features[f].u_j,
                                      visionSqrtInfo());
      double r[2];
      ASSERT_TRUE(single.Evaluate(p.data(), r, nullptr));
      for (int i = 0; i < 2; ++i) worst_row = std::max(worst_row, std::abs(r[i] - rows[2 * f + i]));
    }
    worst = std::max(
        worst, test::worstJacobianError(
                   stacked, x, {&pose_manifold, &pose_manifold, &pose_manifold, &sphere, nullptr}));
  }
  EXPECT_LT(worst_row, 1e-12);
  EXPECT_LT(worst, 1e-5);
}

/// Both forms of the same plane pair in a Ceres problem: one block per feature with the loss
/// given to Ceres, or one stacked block with the loss inside. The mount is held, as in the
/// estimator.
struct TwoProblems {
  std::vector<std::vector<double>> per_feature_x, stacked_x;
  ceres::Problem per_feature, stacked;
  ceres::CauchyLoss loss{1.0};
  PoseManifold pose_manifold;
  ceres::SphereManifold<3> sphere;

  explicit TwoProblems(const PlaneScene& scene) : per_feature(options()), stacked(options()) {
    per_feature_x = stacked_x = scene.blocks();
    for (const auto& feature : scene.features)
      per_feature.AddResidualBlock(
          HomographyResidual::create(feature.u_i, feature.u_j, visionSqrtInfo()), &loss,
          blocks(per_feature_x));
    stacked.AddResidualBlock(
        new StackedHomographyResiduals(scene.features, visionSqrtInfo(), &loss), nullptr,
        blocks(stacked_x));
    for (auto [problem, x] : {std::pair{&per_feature, &per_feature_x}, {&stacked, &stacked_x}}) {
      for (int k = 0; k < 3; ++k) problem->SetManifold((*x)[k].data(), &pose_manifold);
      problem->SetManifold((*x)[3].data(), &sphere);
      problem->SetParameterBlockConstant((*x)[2].data());
      problem->SetParameterBlockConstant((*x)[0].data());  // the gauge: frame i
    }
  }
  static std::vector<double*> blocks(std::vector<std::vector<double>>& x) {
    std::vector<double*> p;
    for (auto& b : x) p.push_back(b.data());
    return p;
  }
  static ceres::Problem::Options options() {
    ceres::Problem::Options o;
    o.loss_function_ownership = o.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    return o;
  }
};

/// Cost, gradient and JᵀJ (over the moving blocks' tangent spaces) of a problem.
struct Linearization {
  double cost = 0;
  Eigen::VectorXd gradient;
  Eigen::MatrixXd JtJ;
};

Linearization linearize(ceres::Problem& problem, const std::vector<double*>& blocks) {
  ceres::Problem::EvaluateOptions options;
  options.parameter_blocks = blocks;
  Linearization l;
  std::vector<double> gradient;
  ceres::CRSMatrix crs;
  EXPECT_TRUE(problem.Evaluate(options, &l.cost, nullptr, &gradient, &crs));
  l.gradient = Eigen::Map<Eigen::VectorXd>(gradient.data(), gradient.size());
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(crs.num_rows, crs.num_cols);
  for (int row = 0; row < crs.num_rows; ++row)
    for (int a = crs.rows[row]; a < crs.rows[row + 1]; ++a) J(row, crs.cols[a]) = crs.values[a];
  l.JtJ = J.transpose() * J;
  return l;
}

TEST(StackedHomographyFactorTest, WithTheLossInsideItIsThePerFeatureBlocksWithCeresLoss) {
  std::mt19937_64 rng(8);
  for (int trial = 0; trial < 10; ++trial) {
    const PlaneScene scene(rng, 12);
    TwoProblems two(scene);
    // Away from the solution: frame j moved 3 cm, the plane's offset 5 % off.
    for (auto* x : {&two.per_feature_x, &two.stacked_x}) {
      (*x)[1][1] += 0.03;
      (*x)[4][0] *= 1.05;
    }
    const auto moving = [](std::vector<std::vector<double>>& x) {
      return std::vector<double*>{x[1].data(), x[3].data(), x[4].data()};
    };
    const Linearization a = linearize(two.per_feature, moving(two.per_feature_x));
    const Linearization b = linearize(two.stacked, moving(two.stacked_x));
    EXPECT_NEAR(b.cost, a.cost, 1e-12 * a.cost);
    EXPECT_LT((b.gradient - a.gradient).norm(), 1e-10 * a.gradient.norm());
    EXPECT_LT((b.JtJ - a.JtJ).norm(), 1e-10 * a.JtJ.norm());

    // The solves take the same steps to the same point. The plane's offset is held: with frame
    // i, it sets the scale that a homography leaves free.
    two.per_feature.SetParameterBlockConstant(two.per_feature_x[4].data());
    two.stacked.SetParameterBlockConstant(two.stacked_x[4].data());
    ceres::Solver::Options solver;
    solver.trust_region_strategy_type = ceres::DOGLEG;
    solver.linear_solver_type = ceres::DENSE_QR;
    ceres::Solver::Summary per_feature_summary, stacked_summary;
    ceres::Solve(solver, &two.per_feature, &per_feature_summary);
    ceres::Solve(solver, &two.stacked, &stacked_summary);
    EXPECT_EQ(stacked_summary.iterations.size(), per_feature_summary.iterations.size());
    EXPECT_NEAR(stacked_summary.final_cost, per_feature_summary.final_cost,
                1e-9 * per_feature_summary.final_cost);
    for (int k : {1, 3})
      for (size_t i = 0; i < two.stacked_x[k].size(); ++i)
        EXPECT_NEAR(two.stacked_x[k][i], two.per_feature_x[k][i], 1e-9);
  }
}

}  // namespace
}  // namespace rpvio
