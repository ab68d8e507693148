#include "mrpt_modules/factors/marginalization.h"

#include <Eigen/Dense>
#include <algorithm>
#include <map>

#include "mrpt_modules/factors/parameter_blocks.h"
#include "mrpt_modules/factors/pose_manifold.h"
#include "mrpt_modules/factors/robust_correction.h"
#include "mrpt_modules/imu/so3.h"

namespace rpvio {
namespace {

using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

bool isPose(int size) { return size == kPoseSize; }
int tangentSize(int size) { return isPose(size) ? kPoseLocalSize : size; }

/// Inverse right Jacobian of SO(3): Log(Exp(w) Exp(δ)) ≈ w + J_r⁻¹(w) δ.
Eigen::Matrix3d inverseRightJacobian(const Eigen::Vector3d& w) {
  const double a = w.norm();
  const Eigen::Matrix3d W = hat(w);
  if (a < 1e-6) return Eigen::Matrix3d::Identity() + 0.5 * W + W * W / 12.0;
  return Eigen::Matrix3d::Identity() + 0.5 * W +
         (1 / (a * a) - (1 + std::cos(a)) / (2 * a * std::sin(a))) * W * W;
}

/// Tangent Jacobian → Jacobian w.r.t. the 7 ambient numbers of a pose (pose_manifold.h).
Eigen::MatrixXd tangentToAmbientDynamic(const Eigen::MatrixXd& J_tangent, const double* pose) {
  Eigen::Matrix<double, 6, 6> inv = Eigen::Matrix<double, 6, 6>::Identity();
  inv.bottomRightCorner<3, 3>() *= 4.0;  // (PᵀP)⁻¹, P = PlusJacobian
  return J_tangent * inv * posePlusJacobian(pose).transpose();
}

}  // namespace

bool MarginalizationPrior::involves(const double* block) const {
  return std::find(blocks.begin(), blocks.end(), block) != blocks.end();
}

MarginalizationFactor::MarginalizationFactor(std::shared_ptr<const MarginalizationPrior> prior)
    : prior_(std::move(prior)) {
  int offset = 0;
  for (int size : prior_->sizes) {
    mutable_parameter_block_sizes()->push_back(size);
    offsets_.push_back(offset);
    offset += tangentSize(size);
  }
  set_num_residuals(static_cast<int>(prior_->r0.size()));
}

bool MarginalizationFactor::Evaluate(double const* const* x, double* residuals,
                                     double** jacobians) const {
  const Eigen::MatrixXd& J = prior_->J;
  Eigen::VectorXd dx(J.cols());
  const auto& sizes = parameter_block_sizes();
  for (size_t b = 0; b < sizes.size(); ++b) {
    const double* x0 = prior_->x0[b].data();
    if (isPose(sizes[b])) {
      dx.segment<3>(offsets_[b]) = posePosition(x[b]) - posePosition(x0);
      const Eigen::AngleAxisd d(poseRotation(x0).conjugate() * poseRotation(x[b]));
      dx.segment<3>(offsets_[b] + 3) = d.angle() * d.axis();
    } else {
      for (int i = 0; i < sizes[b]; ++i) dx(offsets_[b] + i) = x[b][i] - x0[i];
    }
  }
  Eigen::Map<Eigen::VectorXd>(residuals, num_residuals()) = prior_->r0 + J * dx;
  if (!jacobians) return true;
  for (size_t b = 0; b < sizes.size(); ++b) {
    if (!jacobians[b]) continue;
    Eigen::Map<RowMajorMatrix> out(jacobians[b], num_residuals(), sizes[b]);
    const int tan = tangentSize(sizes[b]);
    if (!isPose(sizes[b])) {
      out = J.middleCols(offsets_[b], tan);
      continue;
    }
    // d(x ⊞ δ ⊟ x0)/dδ = diag(I, J_r⁻¹(Log(q0⁻¹ q))).
    Eigen::MatrixXd J_tangent = J.middleCols(offsets_[b], tan);
    J_tangent.rightCols<3>() *= inverseRightJacobian(dx.segment<3>(offsets_[b] + 3));
    out = tangentToAmbientDynamic(J_tangent, x[b]);
  }
  return true;
}

void Marginalizer::addFactor(std::unique_ptr<ceres::CostFunction> cost,
                             std::shared_ptr<ceres::LossFunction> loss,
                             std::vector<double*> blocks) {
  factors_.push_back({std::move(cost), std::move(loss), std::move(blocks)});
}

std::shared_ptr<const MarginalizationPrior> Marginalizer::marginalize(
    const std::set<const double*>& remove) const {
  // Tangent layout: removed blocks first, then kept ones, each in order of first appearance
  // (never by address, so that runs are reproducible).
  std::vector<const Factor*> used;
  std::vector<double*> removed, kept;
  std::map<const double*, int> size_of;
  for (const auto& f : factors_) {
    if (std::none_of(f.blocks.begin(), f.blocks.end(),
                     [&](const double* b) { return remove.count(b) > 0; }))
      continue;
    used.push_back(&f);
    for (size_t k = 0; k < f.blocks.size(); ++k) {
      double* b = f.blocks[k];
      if (size_of.count(b) || constant_.count(b)) continue;
      size_of[b] = f.cost->parameter_block_sizes()[k];
      (remove.count(b) ? removed : kept).push_back(b);
    }
  }
  if (kept.empty()) return nullptr;
  std::map<const double*, int> offset;
  int m = 0, n = 0;
  for (double* b : removed) offset[b] = m, m += tangentSize(size_of[b]);
  n = m;
  for (double* b : kept) offset[b] = n, n += tangentSize(size_of[b]);
  const int kept_size = n - m;

  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(n);
  // Each factor: its Jacobian over its moving blocks' tangent spaces side by side (constant
  // blocks get none), robustified, then JᵀJ and Jᵀr scattered into H and g block by block.
  std::vector<RowMajorMatrix> block_jacobians;  // ambient, as the cost function writes them
  std::vector<double*> J_ptrs;
  std::vector<int> column_of;  // a block's first column in J, -1 when constant
  for (const Factor* f : used) {
    const int rows = f->cost->num_residuals();
    const auto& sizes = f->cost->parameter_block_sizes();
    column_of.assign(sizes.size(), -1);
    int cols = 0;
    J_ptrs.assign(sizes.size(), nullptr);
    if (block_jacobians.size() < sizes.size()) block_jacobians.resize(sizes.size());
    for (size_t k = 0; k < sizes.size(); ++k) {
      if (constant_.count(f->blocks[k])) continue;
      column_of[k] = cols;
      cols += tangentSize(sizes[k]);
      block_jacobians[k].resize(rows, sizes[k]);
      J_ptrs[k] = block_jacobians[k].data();
    }
    Eigen::VectorXd r(rows);
    Eigen::MatrixXd J(rows, cols);
    if (!f->cost->Evaluate(f->blocks.data(), r.data(), J_ptrs.data())) continue;
    for (size_t k = 0; k < sizes.size(); ++k) {
      if (column_of[k] < 0) continue;
      if (isPose(sizes[k]))
        J.middleCols(column_of[k], kPoseLocalSize) =
            block_jacobians[k] * posePlusJacobian(f->blocks[k]);
      else
        J.middleCols(column_of[k], sizes[k]) = block_jacobians[k];
    }
    if (f->loss) {
      const RobustCorrection robust(*f->loss, r.squaredNorm());
      robust.correctJacobian(r, J);
      robust.correctResidual(r);
    }
    Eigen::MatrixXd JtJ(cols, cols);
    JtJ.setZero();
    JtJ.selfadjointView<Eigen::Lower>().rankUpdate(J.transpose());
    JtJ.triangularView<Eigen::StrictlyUpper>() = JtJ.transpose();
    const Eigen::VectorXd Jtr = J.transpose() * r;
    for (size_t a = 0; a < sizes.size(); ++a) {
      if (column_of[a] < 0) continue;
      const int oa = offset[f->blocks[a]], na = tangentSize(sizes[a]);
      g.segment(oa, na) += Jtr.segment(column_of[a], na);
      for (size_t b = 0; b < sizes.size(); ++b)
        if (column_of[b] >= 0)
          H.block(oa, offset[f->blocks[b]], na, tangentSize(sizes[b])) +=
              JtJ.block(column_of[a], column_of[b], na, tangentSize(sizes[b]));
    }
  }

  // Removed scalar blocks that share no factor (the inverse depths) have a diagonal block in H:
  // they are eliminated first, by division, H' = H − H·s D⁻¹ Hs· over the other indices. What
  // remains of the removed set (the oldest frame's pose and speed/bias) takes the pseudo-inverse
  // below. For a positive semi-definite H both give the same complement as the pseudo-inverse
  // of the whole removed block, at a fraction of its eigendecomposition.
  const double eps = 1e-8;
  std::vector<int> scalar, rest;  // indices into H
  for (double* b : removed) {
    const int size = tangentSize(size_of[b]), o = offset[b];
    if (size == 1 && H(o, o) > eps)
      scalar.push_back(o);
    else
      for (int i = o; i < o + size; ++i) rest.push_back(i);
  }
  Eigen::MatrixXd H_ss = H(scalar, scalar);
  if (!H_ss.isDiagonal(0.0)) {  // linked: all by pseudo-inverse
    rest.insert(rest.end(), scalar.begin(), scalar.end());
    scalar.clear();
    H_ss.resize(0, 0);
  }
  const int m_rest = static_cast<int>(rest.size());
  for (int i = n - kept_size; i < n; ++i) rest.push_back(i);
  const Eigen::VectorXd D_inv = H_ss.diagonal().cwiseInverse();
  const Eigen::MatrixXd H_rs = H(rest, scalar);
  const Eigen::MatrixXd H_r = H(rest, rest) - H_rs * D_inv.asDiagonal() * H_rs.transpose();
  const Eigen::VectorXd g_r = g(rest) - H_rs * D_inv.asDiagonal() * g(scalar);

  // Schur complement: H* = Hkk − Hkm Hmm⁻¹ Hmk, g* = gk − Hkm Hmm⁻¹ gm (Hmm⁻¹ pseudo-inverse).
  const Eigen::MatrixXd Hmm =
      0.5 * (H_r.topLeftCorner(m_rest, m_rest) + H_r.topLeftCorner(m_rest, m_rest).transpose());
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig_m(Hmm);
  const Eigen::VectorXd inv_values =
      (eig_m.eigenvalues().array() > eps).select(eig_m.eigenvalues().array().inverse(), 0);
  const Eigen::MatrixXd Hmm_inv =
      eig_m.eigenvectors() * inv_values.asDiagonal() * eig_m.eigenvectors().transpose();
  const Eigen::MatrixXd Hkm = H_r.bottomLeftCorner(kept_size, m_rest);
  const Eigen::MatrixXd H_prior =
      H_r.bottomRightCorner(kept_size, kept_size) - Hkm * Hmm_inv * Hkm.transpose();
  const Eigen::VectorXd g_prior = g_r.tail(kept_size) - Hkm * Hmm_inv * g_r.head(m_rest);

  // H* = Jᵀ J and g* = Jᵀ r0: J = S^½ Vᵀ, r0 = S^-½ Vᵀ g* over the well-determined directions.
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (H_prior + H_prior.transpose()));
  const Eigen::ArrayXd s = eig.eigenvalues().array();
  const Eigen::VectorXd sqrt_s = (s > eps).select(s.sqrt(), 0);
  const Eigen::VectorXd inv_sqrt_s = (s > eps).select(s.sqrt().inverse(), 0);
  Eigen::MatrixXd J = sqrt_s.asDiagonal() * eig.eigenvectors().transpose();
  Eigen::VectorXd r0 = inv_sqrt_s.asDiagonal() * eig.eigenvectors().transpose() * g_prior;

  auto prior = std::make_shared<MarginalizationPrior>();
  prior->blocks = kept;
  for (double* b : kept) {
    prior->sizes.push_back(size_of[b]);
    prior->x0.emplace_back(b, b + size_of[b]);
  }
  prior->J = std::move(J);
  prior->r0 = std::move(r0);
  return prior;
}

}  // namespace rpvio
