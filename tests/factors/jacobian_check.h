#pragma once
// Compares a Ceres cost function's Jacobians, moved to the tangent spaces of the blocks'
// manifolds, with central differences taken on those manifolds.
#include <ceres/cost_function.h>
#include <ceres/manifold.h>
#include <Eigen/Core>
#include <vector>

namespace rpvio::test {

/// Largest |analytic − numeric| / max(1, |numeric|) over every block and entry.
inline double worstJacobianError(const ceres::CostFunction& f, std::vector<std::vector<double>> x,
                                 const std::vector<const ceres::Manifold*>& manifolds,
                                 double step = 1e-6) {
  const int n_res = f.num_residuals();
  const auto& sizes = f.parameter_block_sizes();
  std::vector<const double*> params;
  for (auto& b : x) params.push_back(b.data());
  std::vector<std::vector<double>> jac(sizes.size());
  std::vector<double*> jac_ptrs;
  for (size_t b = 0; b < sizes.size(); ++b) {
    jac[b].resize(n_res * sizes[b]);
    jac_ptrs.push_back(jac[b].data());
  }
  std::vector<double> r0(n_res);
  f.Evaluate(params.data(), r0.data(), jac_ptrs.data());
  double worst = 0;
  for (size_t b = 0; b < sizes.size(); ++b) {
    const int amb = sizes[b];
    const int tan = manifolds[b] ? manifolds[b]->TangentSize() : amb;
    Eigen::MatrixXd plus_jac = Eigen::MatrixXd::Identity(amb, tan);
    if (manifolds[b]) {
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> pj(amb, tan);
      manifolds[b]->PlusJacobian(x[b].data(), pj.data());
      plus_jac = pj;
    }
    const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>
        J_amb(jac[b].data(), n_res, amb);
    const Eigen::MatrixXd analytic = J_amb * plus_jac;
    const std::vector<double> original = x[b];
    for (int k = 0; k < tan; ++k) {
      std::vector<double> r_plus(n_res), r_minus(n_res), delta(tan, 0.0);
      for (double sign : {1.0, -1.0}) {
        delta[k] = sign * step;
        if (manifolds[b]) {
          manifolds[b]->Plus(original.data(), delta.data(), x[b].data());
        } else {
          x[b] = original;
          x[b][k] += delta[k];
        }
        std::vector<const double*> p;
        for (auto& blk : x) p.push_back(blk.data());
        f.Evaluate(p.data(), sign > 0 ? r_plus.data() : r_minus.data(), nullptr);
      }
      x[b] = original;
      for (int i = 0; i < n_res; ++i) {
        const double numeric = (r_plus[i] - r_minus[i]) / (2 * step);
        const double e = std::abs(analytic(i, k) - numeric) / std::max(1.0, std::abs(numeric));
        if (getenv("RPVIO_DEBUG") && e > 1e-5)
          std::printf("block %zu residual %d tangent %d: analytic %g numeric %g\n", b, i, k,
                      analytic(i, k), numeric);
        worst = std::max(worst, e);
      }
    }
  }
  return worst;
}

}  // namespace rpvio::test
