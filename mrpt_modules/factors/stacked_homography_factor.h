#pragma once
// The homography factors (homography_factor.h) of every feature of one plane between an anchor
// frame i and a frame j as one Ceres residual block: 2 rows per feature and, with a loss, one
// last row of zero Jacobian. Each feature's rows carry its own loss, applied inside as Ceres
// applies a block's (robust_correction.h); the last row, √Σₖ(ρ(sₖ) − |r'ₖ|²), makes the block's
// cost ½Σₖρ(sₖ), the features' robust costs. So the solver's cost, gradient, Gauss–Newton model
// and steps are those of one block per feature with the loss attached, without Ceres' per-block
// work (its checks, its Schur updates) and with the poses' rotations computed once per pair.
// Exact for losses with ρ'' ≤ 0 (Huber, soft L1, Cauchy, arctan), where ρ(s) ≥ ρ'(s) s.
// Not evaluable (false) where any of its features is not (homographyInTangent).
// Blocks: pose_i [7], pose_j [7], T_BC [7], plane normal [3], plane distance [1].
#include <ceres/cost_function.h>
#include <ceres/loss_function.h>
#include <Eigen/Core>
#include <vector>

namespace rpvio {

class StackedHomographyResiduals : public ceres::CostFunction {
 public:
  struct Feature {
    Eigen::Vector2d u_i, u_j;  // normalized points in frames i and j
  };
  /// `loss` is borrowed (nullptr: none).
  StackedHomographyResiduals(std::vector<Feature> features, double sqrt_info,
                             const ceres::LossFunction* loss);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  std::vector<Feature> features_;
  double sqrt_info_;
  const ceres::LossFunction* loss_;
};

}  // namespace rpvio
