#pragma once
// Ceres' robust corrector (internal/ceres/corrector.cc; Triggs et al., "Bundle adjustment — a
// modern synthesis", 2000, §4.3): a loss ρ folded into a residual r and its Jacobian J so that
// the Gauss–Newton model of ½ρ(|r|²) is that of ½|r'|²,
//   r' = √ρ' / (1 − α) r,   J' = √ρ' (I − α r rᵀ / |r|²) J,   α = 1 − √(1 + 2|r|² ρ''/ρ'),
// with the curvature term dropped (α = 0) where ρ'' ≤ 0, as Ceres does.
#include <ceres/loss_function.h>

#include <cmath>

namespace rpvio {

class RobustCorrection {
 public:
  RobustCorrection(const ceres::LossFunction& loss, double squared_norm) {
    double rho[3];
    loss.Evaluate(squared_norm, rho);
    cost_ = rho[0];
    sqrt_rho1_ = residual_scaling_ = std::sqrt(rho[1]);
    if (squared_norm > 0 && rho[2] > 0) {
      const double alpha = 1 - std::sqrt(1 + 2 * squared_norm * rho[2] / rho[1]);
      residual_scaling_ = sqrt_rho1_ / (1 - alpha);
      alpha_sq_norm_ = alpha / squared_norm;
    }
  }
  /// ρ(|r|²).
  double cost() const { return cost_; }
  /// J' of one block's columns of J, from the uncorrected r.
  template <typename Residual, typename Jacobian>
  void correctJacobian(const Residual& r, Jacobian& J) const {
    if (alpha_sq_norm_ == 0)
      J *= sqrt_rho1_;
    else
      J = sqrt_rho1_ * (J - alpha_sq_norm_ * r * (r.transpose() * J));
  }
  template <typename Residual>
  void correctResidual(Residual& r) const {
    r *= residual_scaling_;
  }

 private:
  double cost_ = 0, sqrt_rho1_ = 1, residual_scaling_ = 1, alpha_sq_norm_ = 0;
};

}  // namespace rpvio
