#include "mrpt_modules/factors/time_offset_reprojection_factor.h"

#include <ceres/autodiff_cost_function.h>

namespace rpvio {

ceres::CostFunction* TimeOffsetReprojectionResidual::create(const Eigen::Vector2d& u_i,
                                                            const Eigen::Vector2d& v_i,
                                                            const Eigen::Vector2d& u_j,
                                                            const Eigen::Vector2d& v_j,
                                                            double sqrt_info) {
  return new ceres::AutoDiffCostFunction<TimeOffsetReprojectionResidual, 2, 7, 7, 7, 1, 1>(
      new TimeOffsetReprojectionResidual(u_i, v_i, u_j, v_j, sqrt_info));
}

}  // namespace rpvio
