#pragma once
// The manifold of a pose block [p, q] (mrpt_modules/factors/parameter_blocks.h): p + δp and
// q ⊗ Exp(δθ) (right perturbation, body frame), with its true Plus Jacobian so that autodiff
// factors (which differentiate w.r.t. the 7 ambient numbers) and analytic factors (which know
// their tangent-space Jacobian, lifted with tangentToAmbient) can share a pose.
#include <ceres/manifold.h>
#include <Eigen/Core>

namespace rpvio {

class PoseManifold : public ceres::Manifold {
 public:
  int AmbientSize() const override { return 7; }
  int TangentSize() const override { return 6; }
  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override;
  bool PlusJacobian(const double* x, double* jacobian) const override;
  bool Minus(const double* y, const double* x, double* y_minus_x) const override;
  bool MinusJacobian(const double* x, double* jacobian) const override;
};

/// A pose whose position and yaw are held (the gauge of a visual-inertial window, which cannot
/// observe them): only its tilt moves, q ↦ Exp([δ₀, δ₁, 0]) ⊗ q (left perturbation about the
/// world's horizontal axes), p fixed.
class TiltOnlyPoseManifold : public ceres::Manifold {
 public:
  int AmbientSize() const override { return 7; }
  int TangentSize() const override { return 2; }
  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override;
  bool PlusJacobian(const double* x, double* jacobian) const override;
  bool Minus(const double* y, const double* x, double* y_minus_x) const override;
  bool MinusJacobian(const double* x, double* jacobian) const override;
};

/// d(ambient)/d(tangent) at `pose` (7x6).
Eigen::Matrix<double, 7, 6> posePlusJacobian(const double* pose);

/// An ambient Jacobian J_a (rows x 7) with J_a · PlusJacobian = J_tangent: J_a = J_t ·
/// PlusJacobian⁺.
template <int Rows>
Eigen::Matrix<double, Rows, 7, Eigen::RowMajor> tangentToAmbient(
    const Eigen::Matrix<double, Rows, 6>& J_tangent, const double* pose) {
  const Eigen::Matrix<double, 7, 6> P = posePlusJacobian(pose);
  // PlusJacobian has orthogonal columns (PᵀP = diag(1, 1, 1, ¼, ¼, ¼)): P⁺ = (PᵀP)⁻¹ Pᵀ.
  Eigen::Matrix<double, 6, 6> inv = Eigen::Matrix<double, 6, 6>::Identity();
  inv.bottomRightCorner<3, 3>() *= 4.0;
  return J_tangent * inv * P.transpose();
}

}  // namespace rpvio
