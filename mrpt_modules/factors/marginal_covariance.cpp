#include "mrpt_modules/factors/marginal_covariance.h"

#include <ceres/crs_matrix.h>
#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <set>
#include <vector>

namespace rpvio {

namespace {
constexpr double kFree = 1e-12;  // information added to every direction, relative to its block's
constexpr size_t kDenseRowEntries = 48;  // a factor row: ≤ 4 poses and planes (~30 entries)
}  // namespace

std::optional<Eigen::MatrixXd> marginalCovariance(ceres::Problem& problem,
                                                  const std::vector<double*>& wanted) {
  // Column order: the wanted blocks, the other blocks kept dense, then the scalar blocks to
  // eliminate first; each group in the order the residuals were added (GetParameterBlocks orders
  // by address, which would make the sums, hence the run, differ from one run to the next).
  std::vector<ceres::ResidualBlockId> residuals;
  problem.GetResidualBlocks(&residuals);
  std::vector<double*> ordered = wanted, scalars;
  std::set<double*> seen(wanted.begin(), wanted.end());
  for (const ceres::ResidualBlockId residual : residuals) {
    std::vector<double*> blocks;
    problem.GetParameterBlocksForResidualBlock(residual, &blocks);
    for (double* block : blocks) {
      if (problem.IsParameterBlockConstant(block) || !seen.insert(block).second) continue;
      (problem.ParameterBlockTangentSize(block) == 1 ? scalars : ordered).push_back(block);
    }
  }
  int wanted_size = 0, dense_size = 0;
  for (double* block : wanted) wanted_size += problem.ParameterBlockTangentSize(block);
  for (double* block : ordered) dense_size += problem.ParameterBlockTangentSize(block);
  ordered.insert(ordered.end(), scalars.begin(), scalars.end());

  ceres::Problem::EvaluateOptions evaluate;
  evaluate.parameter_blocks = ordered;
  evaluate.apply_loss_function = true;
  ceres::CRSMatrix crs;
  if (!problem.Evaluate(evaluate, nullptr, nullptr, nullptr, &crs)) return std::nullopt;
  // H = JᵀJ, row by row (a row has ~15 non-zeros: far cheaper than a sparse product). The kept
  // columns' block S is dense and summed on its upper triangle only; the scalar blocks' couplings
  // (H_ek) and their own block (H_ee, diagonal for inverse depths) stay sparse: a dense H would be
  // (kept + ~10³ depths)². Rows dense over the kept columns (the marginalization prior's: most of
  // the work, entry by entry) are summed as one product DᵀD instead.
  const int eliminated = crs.num_cols - dense_size;
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(dense_size, dense_size);
  std::vector<Eigen::Triplet<double>> ek, ee;
  std::vector<int> kept_entries, scalar_entries;  // one row's entries, by column group
  std::vector<int> dense_rows;
  for (int row = 0; row < crs.num_rows; ++row) {
    kept_entries.clear();
    scalar_entries.clear();
    for (int a = crs.rows[row]; a < crs.rows[row + 1]; ++a)
      (crs.cols[a] < dense_size ? kept_entries : scalar_entries).push_back(a);
    if (kept_entries.size() > kDenseRowEntries)
      dense_rows.push_back(row);
    else
      for (size_t i = 0; i < kept_entries.size(); ++i)
        for (size_t j = i; j < kept_entries.size(); ++j) {
          const int a = kept_entries[i], b = kept_entries[j];
          const auto [lo, hi] = std::minmax(crs.cols[a], crs.cols[b]);
          S(lo, hi) += crs.values[a] * crs.values[b];
        }
    for (const int e : scalar_entries) {
      const int scalar = crs.cols[e] - dense_size;
      for (const int f : scalar_entries)
        ee.emplace_back(scalar, crs.cols[f] - dense_size, crs.values[e] * crs.values[f]);
      for (const int k : kept_entries)  // its transpose is not needed
        ek.emplace_back(scalar, crs.cols[k], crs.values[e] * crs.values[k]);
    }
  }
  Eigen::MatrixXd D_transposed =
      Eigen::MatrixXd::Zero(dense_size, static_cast<Eigen::Index>(dense_rows.size()));
  for (size_t i = 0; i < dense_rows.size(); ++i)
    for (int a = crs.rows[dense_rows[i]]; a < crs.rows[dense_rows[i] + 1]; ++a)
      if (crs.cols[a] < dense_size)
        D_transposed(crs.cols[a], static_cast<Eigen::Index>(i)) = crs.values[a];
  if (!dense_rows.empty())  // Eigen's product blocking divides by the inner size
    S.selfadjointView<Eigen::Upper>().rankUpdate(D_transposed);
  S.triangularView<Eigen::StrictlyLower>() = S.transpose();

  // Schur complement of the scalar blocks, sparse (a depth touches a few poses):
  // S = H_kk − H_ke H_ee⁻¹ H_ek.
  if (eliminated > 0) {
    Eigen::SparseMatrix<double> H_ek(eliminated, dense_size), H_ee(eliminated, eliminated);
    H_ek.setFromTriplets(ek.begin(), ek.end());
    H_ee.setFromTriplets(ee.begin(), ee.end());
    H_ek.prune(0.0);  // entries that sum to exactly 0 are not structure
    H_ee.prune(0.0);
    for (int i = 0; i < eliminated; ++i)
      H_ee.coeffRef(i, i) += kFree * std::max(H_ee.coeff(i, i), 1.0);
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(H_ee);
    if (ldlt.info() != Eigen::Success) return std::nullopt;
    const Eigen::SparseMatrix<double> X = ldlt.solve(H_ek);
    S -= Eigen::MatrixXd(Eigen::SparseMatrix<double>(H_ek.transpose()) * X);
  }
  // Jacobi-scaled (unit diagonal: the blocks' information differs by ten orders of magnitude,
  // velocities against biases), plus kFree: a direction the information leaves free (a plane that
  // window cannot see the tilt of) gets an enormous variance instead of failing every block.
  Eigen::VectorXd scale = S.diagonal();
  for (Eigen::Index i = 0; i < scale.size(); ++i)
    scale(i) = 1 / std::sqrt(scale(i) > 0 ? scale(i) : 1);
  Eigen::MatrixXd scaled = scale.asDiagonal() * S * scale.asDiagonal();
  scaled.diagonal().array() += kFree;
  const Eigen::LDLT<Eigen::MatrixXd> factor(scaled);
  if (factor.info() != Eigen::Success) return std::nullopt;
  const Eigen::MatrixXd columns =
      factor.solve(Eigen::MatrixXd::Identity(dense_size, dense_size).leftCols(wanted_size));
  const Eigen::VectorXd wanted_scale = scale.head(wanted_size);
  return Eigen::MatrixXd(wanted_scale.asDiagonal() * columns.topRows(wanted_size) *
                         wanted_scale.asDiagonal());
}

}  // namespace rpvio
