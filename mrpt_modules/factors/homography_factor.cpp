#include "mrpt_modules/factors/homography_factor.h"

#include <ceres/autodiff_cost_function.h>

namespace rpvio {

double visionSqrtInfo(double focal_px, double sigma_px) { return focal_px / sigma_px; }

ceres::CostFunction* HomographyResidual::create(const Eigen::Vector2d& u_i,
                                                const Eigen::Vector2d& u_j, double sqrt_info) {
  return new ceres::AutoDiffCostFunction<HomographyResidual, 2, 7, 7, 7, 3, 1>(
      new HomographyResidual(u_i, u_j, sqrt_info));
}

}  // namespace rpvio
