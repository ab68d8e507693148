#pragma once
// A prior on the accelerometer bias of the window's first keyframe, at the initializer's estimate
// b₀ with the standard deviation σ of the IMU's turn-on bias:
//   r = (b_a − b₀) / σ.
// At constant heading the IMU cannot tell a tilt θ from a horizontal bias g·θ; without this prior
// the first window solves walked along that direction (the car: 6° of roll against a 1.1 m/s²
// bias within 0.1 s). Later keyframes inherit it through the bias random walk and, once the
// keyframe is marginalized, through the prior.
// Block: speed_bias [9] = (v, b_a, b_g). Residual: 3.
#include <ceres/sized_cost_function.h>
#include <Eigen/Core>

namespace rpvio {

class AccelBiasPriorResidual : public ceres::SizedCostFunction<3, 9> {
 public:
  AccelBiasPriorResidual(const Eigen::Vector3d& bias, double sigma)
      : bias_(bias), sqrt_info_(1 / sigma) {}
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  Eigen::Vector3d bias_;
  double sqrt_info_;
};

}  // namespace rpvio
