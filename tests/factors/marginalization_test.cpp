// Marginalization prior: exact on a linear Gaussian problem (eliminating blocks and solving what
// remains gives the full solution; also with scalar blocks eliminated by division, and with
// scalars that share a factor), and its Jacobians on pose blocks agree with numeric
// derivatives on the manifold away from the linearization point.
#include <gtest/gtest.h>

#include <ceres/ceres.h>

#include <algorithm>
#include <random>

#include "mrpt_modules/factors/marginalization.h"
#include "mrpt_modules/factors/pose_manifold.h"
#include "mrpt_modules/factors/reprojection_factor.h"
#include "tests/factors/jacobian_check.h"

namespace rpvio {
namespace {

/// r = Σ A_k x_k − b on Euclidean blocks.
class LinearFactor : public ceres::CostFunction {
 public:
  LinearFactor(std::vector<Eigen::MatrixXd> A, Eigen::VectorXd b) : A_(std::move(A)), b_(b) {
    for (const auto& a : A_) mutable_parameter_block_sizes()->push_back(static_cast<int>(a.cols()));
    set_num_residuals(static_cast<int>(b_.size()));
  }
  bool Evaluate(double const* const* x, double* r, double** J) const override {
    Eigen::Map<Eigen::VectorXd> res(r, num_residuals());
    res = -b_;
    for (size_t k = 0; k < A_.size(); ++k) {
      res += A_[k] * Eigen::Map<const Eigen::VectorXd>(x[k], A_[k].cols());
      if (J && J[k])
        Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
            J[k], num_residuals(), A_[k].cols()) = A_[k];
    }
    return true;
  }

 private:
  std::vector<Eigen::MatrixXd> A_;
  Eigen::VectorXd b_;
};

TEST(Marginalization, ExactOnLinearProblem) {
  std::mt19937 rng(7);
  std::normal_distribution<double> N(0, 1);
  auto random = [&](int r, int c) {
    return Eigen::MatrixXd(Eigen::MatrixXd::NullaryExpr(r, c, [&] { return N(rng); }));
  };
  // Chain x0 — x1 — x2 — x3 (sizes 2, 3, 1, 2) plus a factor x0 — x2.
  std::vector<std::vector<double>> x = {{0.3, -1}, {0.1, 0.2, 0.5}, {2}, {-0.4, 0.9}};
  struct Spec {
    std::vector<int> blocks;
  };
  const std::vector<Spec> specs = {{{0}}, {{0, 1}}, {{1, 2}}, {{2, 3}}, {{0, 2}}, {{3}}};
  std::vector<std::vector<Eigen::MatrixXd>> A;
  std::vector<Eigen::VectorXd> b;
  for (const auto& s : specs) {
    A.emplace_back();
    for (int k : s.blocks) A.back().push_back(random(3, static_cast<int>(x[k].size())));
    b.push_back(random(3, 1));
  }
  auto factor = [&](size_t i) { return new LinearFactor(A[i], b[i]); };
  auto blocks = [&](size_t i, std::vector<std::vector<double>>& v) {
    std::vector<double*> p;
    for (int k : specs[i].blocks) p.push_back(v[k].data());
    return p;
  };
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.function_tolerance = options.gradient_tolerance = options.parameter_tolerance = 1e-16;
  // Full problem.
  auto full = x;
  ceres::Problem problem_full;
  for (size_t i = 0; i < specs.size(); ++i)
    problem_full.AddResidualBlock(factor(i), nullptr, blocks(i, full));
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem_full, &summary);
  // Eliminate x0 and x1, then solve for x2, x3 with the prior.
  auto reduced = x;
  Marginalizer marginalizer;
  for (size_t i = 0; i < specs.size(); ++i)
    marginalizer.addFactor(std::unique_ptr<ceres::CostFunction>(factor(i)), nullptr,
                           blocks(i, reduced));
  const auto prior = marginalizer.marginalize({reduced[0].data(), reduced[1].data()});
  ASSERT_NE(prior, nullptr);
  ASSERT_EQ(prior->blocks.size(), 1u);  // only x2 is linked to x0/x1
  EXPECT_EQ(prior->blocks[0], reduced[2].data());
  ceres::Problem problem_reduced;
  problem_reduced.AddResidualBlock(new MarginalizationFactor(prior), nullptr, prior->blocks);
  for (size_t i : {3, 5}) problem_reduced.AddResidualBlock(factor(i), nullptr, blocks(i, reduced));
  ceres::Solve(options, &problem_reduced, &summary);
  for (int k : {2, 3})
    for (size_t i = 0; i < x[k].size(); ++i) EXPECT_NEAR(reduced[k][i], full[k][i], 1e-8);
}

/// Eliminating `removed` (indices into x) from the linear factors `specs`, then solving the rest
/// with the prior, gives the full problem's solution of the kept blocks.
void expectExactElimination(const std::vector<std::vector<int>>& specs,
                            const std::vector<std::vector<double>>& x,
                            const std::vector<int>& removed) {
  std::mt19937 rng(11);
  std::normal_distribution<double> N(0, 1);
  std::vector<std::vector<Eigen::MatrixXd>> A;
  std::vector<Eigen::VectorXd> b;
  for (const auto& blocks : specs) {
    A.emplace_back();
    for (int k : blocks)
      A.back().push_back(
          Eigen::MatrixXd::NullaryExpr(3, static_cast<int>(x[k].size()), [&] { return N(rng); }));
    b.push_back(Eigen::VectorXd::NullaryExpr(3, [&] { return N(rng); }));
  }
  auto pointers = [&](size_t i, std::vector<std::vector<double>>& v) {
    std::vector<double*> p;
    for (int k : specs[i]) p.push_back(v[k].data());
    return p;
  };
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  // Tight enough for 1e-8, loose enough to end in convergence (a failed solve keeps x).
  options.function_tolerance = options.parameter_tolerance = 1e-16;
  options.gradient_tolerance = 1e-13;
  ceres::Solver::Summary summary;
  auto full = x;
  ceres::Problem problem_full;
  for (size_t i = 0; i < specs.size(); ++i)
    problem_full.AddResidualBlock(new LinearFactor(A[i], b[i]), nullptr, pointers(i, full));
  ceres::Solve(options, &problem_full, &summary);
  ASSERT_TRUE(summary.IsSolutionUsable());
  auto reduced = x;
  Marginalizer marginalizer;
  std::set<const double*> remove;
  for (int k : removed) remove.insert(reduced[k].data());
  std::vector<size_t> untouched;  // factors on kept blocks only
  for (size_t i = 0; i < specs.size(); ++i) {
    const bool touches = std::any_of(specs[i].begin(), specs[i].end(), [&](int k) {
      return std::find(removed.begin(), removed.end(), k) != removed.end();
    });
    if (touches)
      marginalizer.addFactor(std::make_unique<LinearFactor>(A[i], b[i]), nullptr,
                             pointers(i, reduced));
    else
      untouched.push_back(i);
  }
  const auto prior = marginalizer.marginalize(remove);
  ASSERT_NE(prior, nullptr);
  ceres::Problem problem_reduced;
  problem_reduced.AddResidualBlock(new MarginalizationFactor(prior), nullptr, prior->blocks);
  for (size_t i : untouched)
    problem_reduced.AddResidualBlock(new LinearFactor(A[i], b[i]), nullptr, pointers(i, reduced));
  ceres::Solve(options, &problem_reduced, &summary);
  ASSERT_TRUE(summary.IsSolutionUsable());
  for (size_t k = 0; k < x.size(); ++k) {
    if (std::find(removed.begin(), removed.end(), k) != removed.end()) continue;
    for (size_t i = 0; i < x[k].size(); ++i) EXPECT_NEAR(reduced[k][i], full[k][i], 1e-8);
  }
}

TEST(Marginalization, ExactWithScalarBlocksEliminatedByDivision) {
  // x0 (3, a "pose") and x1..x4 (scalars, "inverse depths": each in factors with x0 and the kept
  // x5, x6, never with another scalar) are removed; x5, x6 (sizes 3, 2) are kept.
  const std::vector<std::vector<double>> x = {{0.1, 0.2, 0.3},  {1},        {2}, {0.5}, {-1},
                                              {0.3, -0.2, 0.4}, {1.5, -0.5}};
  expectExactElimination({{0},
                          {0, 5},
                          {0, 1, 5},
                          {1, 6},
                          {0, 2, 6},
                          {2, 5},
                          {0, 3, 5},
                          {3, 6},
                          {0, 4, 6},
                          {4, 5, 6},
                          {5, 6},
                          {6}},
                         x, {0, 1, 2, 3, 4});
}

TEST(Marginalization, ExactWhenRemovedScalarsShareAFactor) {
  // x1 and x2 share a factor: their block is not diagonal, all go through the pseudo-inverse.
  const std::vector<std::vector<double>> x = {{0.1, 0.2, 0.3}, {1}, {2}, {0.3, -0.2, 0.4}};
  expectExactElimination({{0}, {0, 1, 3}, {1, 2}, {0, 2, 3}, {2, 3}, {3}}, x, {0, 1, 2});
}

std::vector<double> pose(const Eigen::Vector3d& p, const Eigen::Quaterniond& q) {
  return {p.x(), p.y(), p.z(), q.x(), q.y(), q.z(), q.w()};
}

TEST(Marginalization, PriorJacobiansMatchNumericOnPoses) {
  // Three camera poses see points anchored in pose 0; eliminate pose 0 and the inverse depths.
  const Eigen::Quaterniond q1(Eigen::AngleAxisd(0.1, Eigen::Vector3d(0.2, 1, 0.1).normalized()));
  const Eigen::Quaterniond q2(Eigen::AngleAxisd(-0.15, Eigen::Vector3d(1, 0.3, 0).normalized()));
  std::vector<std::vector<double>> poses = {pose(Eigen::Vector3d::Zero(), {1, 0, 0, 0}),
                                            pose({0.5, 0.1, 0}, q1), pose({1.0, -0.2, 0.1}, q2)};
  std::vector<double> mount = pose(Eigen::Vector3d::Zero(), {1, 0, 0, 0});
  std::vector<std::vector<double>> depths;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-0.4, 0.4);
  for (int k = 0; k < 12; ++k) depths.push_back({1.0 / (3 + 4 * (U(rng) + 0.4))});
  Marginalizer marginalizer;
  for (size_t k = 0; k < depths.size(); ++k) {
    const Eigen::Vector2d u0(U(rng), U(rng));
    for (size_t j = 1; j < poses.size(); ++j) {
      // Observations slightly off the geometry: a non-zero residual to linearize about.
      const Eigen::Vector2d uj(U(rng), U(rng));
      marginalizer.addFactor(
          std::unique_ptr<ceres::CostFunction>(ReprojectionResidual::create(u0, uj, 300)),
          std::make_shared<ceres::CauchyLoss>(1.0),
          {poses[0].data(), poses[j].data(), mount.data(), depths[k].data()});
    }
  }
  marginalizer.setConstant(mount.data());
  std::set<const double*> remove = {poses[0].data()};
  for (auto& d : depths) remove.insert(d.data());
  const auto prior = marginalizer.marginalize(remove);
  ASSERT_NE(prior, nullptr);
  ASSERT_EQ(prior->blocks.size(), 2u);
  // At the linearization point the residual is r0; away from it, compare Jacobians.
  std::vector<std::vector<double>> x = {poses[1], poses[2]};
  const PoseManifold pm;
  const double d1[6] = {0.05, -0.02, 0.03, 0.2, -0.1, 0.15}, d2[6] = {-0.1, 0, 0.02, -0.3, 0.1, 0};
  pm.Plus(poses[1].data(), d1, x[0].data());
  pm.Plus(poses[2].data(), d2, x[1].data());
  const MarginalizationFactor factor(prior);
  const double worst = test::worstJacobianError(factor, x, {&pm, &pm});
  std::printf("marginalization prior: worst Jacobian error %.2e\n", worst);
  EXPECT_LT(worst, 1e-6);
}

}  // namespace
}  // namespace rpvio
