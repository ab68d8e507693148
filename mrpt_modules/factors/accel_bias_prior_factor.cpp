#include "mrpt_modules/factors/accel_bias_prior_factor.h"

namespace rpvio {

bool AccelBiasPriorResidual::Evaluate(double const* const* parameters, double* residuals,
                                      double** jacobians) const {
  const Eigen::Map<const Eigen::Vector3d> bias(parameters[0] + 3);
  Eigen::Map<Eigen::Vector3d> r(residuals);
  r = sqrt_info_ * (bias - bias_);
  if (jacobians && jacobians[0]) {
    Eigen::Map<Eigen::Matrix<double, 3, 9, Eigen::RowMajor>> J(jacobians[0]);
    J.setZero();
    J.block<3, 3>(0, 3).diagonal().setConstant(sqrt_info_);
  }
  return true;
}

}  // namespace rpvio
