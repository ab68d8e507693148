#pragma once
// The IMU factor between frames i and j: the preintegration residual (imu_preintegration.h),
// whitened by the square root of its information, with analytic Jacobians (right perturbation of
// the rotations, lifted to the 7-number pose blocks through PoseManifold).
// Blocks: pose_i [7], speed_bias_i [9], pose_j [7], speed_bias_j [9].
#include <ceres/sized_cost_function.h>
#include <memory>

#include "mrpt_modules/imu/imu_preintegration.h"

namespace rpvio {

class ImuFactor : public ceres::SizedCostFunction<15, 7, 9, 7, 9> {
 public:
  ImuFactor(std::shared_ptr<const ImuPreintegration> preintegration, const Eigen::Vector3d& g_w);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  std::shared_ptr<const ImuPreintegration> pre_;
  Eigen::Vector3d g_w_;
  Eigen::Matrix<double, 15, 15> sqrt_information_;
};

}  // namespace rpvio
