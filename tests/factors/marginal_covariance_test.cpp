// marginalCovariance against ceres::Covariance on a small nonlinear problem with what a window
// has: a block on a manifold (a plane normal), scalar blocks to eliminate (depths), a dense block
// left out (a camera position) and a robust loss.
#include <gtest/gtest.h>

#include <ceres/ceres.h>
#include <ceres/sphere_manifold.h>
#include <random>

#include "mrpt_modules/factors/marginal_covariance.h"

namespace rpvio {
namespace {

/// A point at depth λ along the ray u from the camera c lies on the plane n·X = d.
struct OnPlane {
  Eigen::Vector3d u;
  template <typename T>
  bool operator()(const T* n, const T* d, const T* depth, const T* c, T* r) const {
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> normal(n), camera(c);
    r[0] = normal.dot(camera + depth[0] * u.cast<T>()) - d[0];
    return true;
  }
};

/// A direct measurement of a block: x − z.
template <int N>
struct Measured {
  Eigen::Matrix<double, N, 1> z;
  double sigma;
  template <typename T>
  bool operator()(const T* x, T* r) const {
    for (int i = 0; i < N; ++i) r[i] = (x[i] - z(i)) / sigma;
    return true;
  }
};

/// r = A (x − x0) over the stacked blocks, x0 their values when built: a factor dense over many
/// blocks, like a marginalization prior.
class DenseLinear : public ceres::CostFunction {
 public:
  DenseLinear(const std::vector<double*>& blocks, const std::vector<int>& sizes, int rows) {
    for (size_t b = 0; b < blocks.size(); ++b) {
      mutable_parameter_block_sizes()->push_back(sizes[b]);
      x0_.emplace_back(blocks[b], blocks[b] + sizes[b]);
    }
    set_num_residuals(rows);
    int cols = 0;
    for (int size : sizes) cols += size;
    std::mt19937 rng(5);
    std::normal_distribution<double> N(0, 1);
    A_ = Eigen::MatrixXd::NullaryExpr(rows, cols, [&] { return N(rng); });
  }
  bool Evaluate(double const* const* x, double* residuals, double** jacobians) const override {
    Eigen::Map<Eigen::VectorXd> r(residuals, num_residuals());
    r.setZero();
    int offset = 0;
    for (size_t b = 0; b < parameter_block_sizes().size(); ++b) {
      const int size = parameter_block_sizes()[b];
      r += A_.middleCols(offset, size) * (Eigen::Map<const Eigen::VectorXd>(x[b], size) -
                                          Eigen::Map<const Eigen::VectorXd>(x0_[b].data(), size));
      if (jacobians && jacobians[b])
        Eigen::Map<Eigen::Matrix<double, -1, -1, Eigen::RowMajor>>(
            jacobians[b], num_residuals(), size) = A_.middleCols(offset, size);
      offset += size;
    }
    return true;
  }

 private:
  Eigen::MatrixXd A_;
  std::vector<std::vector<double>> x0_;
};

struct Scene {
  double n[3] = {0.1, 0.2, 0.97};
  double d[1] = {2.0};
  std::vector<std::array<double, 3>> cameras;  // one per few depths, each with a prior
  std::vector<std::array<double, 1>> depths;
  std::vector<std::array<double, 3>> points;
  ceres::Problem problem;
  ceres::SphereManifold<3> sphere;
  ceres::CauchyLoss loss{0.05};

  /// `reversed_storage`: the same problem, its depths and cameras stored in memory in the reverse
  /// order of their residuals.
  /// `dense_factor`: 20 more points of 3 numbers, each measured, all tied to the cameras and the
  /// plane offset by one dense factor (more entries per row than any window factor).
  explicit Scene(bool reversed_storage = false, bool dense_factor = false) : problem(options()) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> U(-0.6, 0.6);
    std::normal_distribution<double> N(0, 0.05);
    depths.resize(25);
    cameras.assign(5, {0.05, -0.1, 0.02});
    for (size_t k = 0; k < depths.size(); ++k) {
      auto& depth = depths[reversed_storage ? depths.size() - 1 - k : k];
      const size_t camera = k % cameras.size();
      auto& c = cameras[reversed_storage ? cameras.size() - 1 - camera : camera];
      const Eigen::Vector3d u = Eigen::Vector3d(U(rng), U(rng), 1).normalized();
      depth[0] = 2.2 + N(rng);
      problem.AddResidualBlock(
          new ceres::AutoDiffCostFunction<OnPlane, 1, 3, 1, 1, 3>(new OnPlane{u}), &loss, n, d,
          depth.data(), c.data());
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<Measured<1>, 1, 1>(
                                   new Measured<1>{Eigen::Matrix<double, 1, 1>(2.2), 0.1}),
                               nullptr, depth.data());
    }
    for (auto& c : cameras)
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<Measured<3>, 3, 3>(
                                   new Measured<3>{Eigen::Vector3d::Zero(), 0.02}),
                               nullptr, c.data());
    if (dense_factor) {
      points.assign(20, {0.3, -0.2, 1.0});
      std::vector<double*> blocks = {d};
      for (auto& c : cameras) blocks.push_back(c.data());
      for (auto& p : points) {
        blocks.push_back(p.data());
        problem.AddResidualBlock(new ceres::AutoDiffCostFunction<Measured<3>, 3, 3>(
                                     new Measured<3>{Eigen::Vector3d(0.3, -0.2, 1.0), 0.01}),
                                 nullptr, p.data());
      }
      std::vector<int> sizes(blocks.size(), 3);
      sizes[0] = 1;
      problem.AddResidualBlock(new DenseLinear(blocks, sizes, 12), nullptr, blocks);
    }
    problem.SetManifold(n, &sphere);
    ceres::Solver::Options solver;
    solver.max_num_iterations = 50;
    ceres::Solver::Summary summary;
    ceres::Solve(solver, &problem, &summary);
  }
  static ceres::Problem::Options options() {
    ceres::Problem::Options o;
    o.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    o.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    return o;
  }
};

/// The covariance of (n, d) in n's tangent space, by ceres::Covariance.
Eigen::Matrix3d ceresCovariance(Scene& scene) {
  ceres::Covariance::Options options;
  options.algorithm_type = ceres::DENSE_SVD;
  ceres::Covariance reference(options);
  EXPECT_TRUE(reference.Compute({{scene.n, scene.n}, {scene.n, scene.d}, {scene.d, scene.d}},
                                &scene.problem));
  Eigen::Matrix<double, 2, 2, Eigen::RowMajor> nn;
  Eigen::Vector2d nd;
  double dd;
  reference.GetCovarianceBlockInTangentSpace(scene.n, scene.n, nn.data());
  reference.GetCovarianceBlockInTangentSpace(scene.n, scene.d, nd.data());
  reference.GetCovarianceBlockInTangentSpace(scene.d, scene.d, &dd);
  Eigen::Matrix3d expected;
  expected << nn, nd, nd.transpose(), dd;
  return expected;
}

TEST(MarginalCovariance, AgreesWithCeresCovariance) {
  Scene scene;
  const auto ours = marginalCovariance(scene.problem, {scene.n, scene.d});
  ASSERT_TRUE(ours.has_value());
  ASSERT_EQ(ours->rows(), 3);  // the normal's 2 tangent numbers, then d
  const Eigen::Matrix3d expected = ceresCovariance(scene);
  EXPECT_LT((*ours - expected).norm(), 1e-8 * expected.norm()) << *ours << "\n\n" << expected;
  // Not the trivial answer: the depths and the camera carry uncertainty into the plane.
  EXPECT_GT(expected(2, 2), 1e-6);
}

TEST(MarginalCovariance, AgreesWithCeresCovarianceWithADenseFactor) {
  Scene scene(false, true), without;
  const auto ours = marginalCovariance(scene.problem, {scene.n, scene.d});
  ASSERT_TRUE(ours.has_value());
  const Eigen::Matrix3d expected = ceresCovariance(scene);
  EXPECT_LT((*ours - expected).norm(), 1e-8 * expected.norm()) << *ours << "\n\n" << expected;
  // The dense factor informs the plane offset.
  EXPECT_LT(expected(2, 2), 0.9 * ceresCovariance(without)(2, 2));
}

TEST(MarginalCovariance, DoesNotDependOnWhereTheBlocksLive) {
  // Runs must repeat exactly: the result may not follow the blocks' addresses.
  Scene scene, reversed(true);
  const auto a = marginalCovariance(scene.problem, {scene.n, scene.d});
  const auto b = marginalCovariance(reversed.problem, {reversed.n, reversed.d});
  ASSERT_TRUE(a.has_value() && b.has_value());
  EXPECT_TRUE(a->cwiseEqual(*b).all()) << "differs by " << (*a - *b).norm();
}

TEST(MarginalCovariance, AFreeDirectionGetsAnEnormousVarianceAndLeavesTheRest) {
  Scene scene;
  const auto observed = marginalCovariance(scene.problem, {scene.n, scene.d});
  double unobserved[2] = {0, 0};  // free, and no residual constrains it
  scene.problem.AddParameterBlock(unobserved, 2);
  const auto with_free = marginalCovariance(scene.problem, {scene.n, scene.d, unobserved});
  ASSERT_TRUE(observed.has_value() && with_free.has_value());
  EXPECT_GT((with_free->bottomRightCorner<2, 2>().diagonal().minCoeff()), 1e9);
  EXPECT_LT(((with_free->topLeftCorner<3, 3>() - *observed).norm()), 1e-9 * observed->norm());
}

}  // namespace
}  // namespace rpvio
