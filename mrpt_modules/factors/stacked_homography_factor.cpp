#include "mrpt_modules/factors/stacked_homography_factor.h"

#include <algorithm>

#include "mrpt_modules/factors/homography_factor.h"
#include "mrpt_modules/factors/parameter_blocks.h"
#include "mrpt_modules/factors/pose_manifold.h"
#include "mrpt_modules/factors/robust_correction.h"

namespace rpvio {

StackedHomographyResiduals::StackedHomographyResiduals(std::vector<Feature> features,
                                                       double sqrt_info,
                                                       const ceres::LossFunction* loss)
    : features_(std::move(features)), sqrt_info_(sqrt_info), loss_(loss) {
  *mutable_parameter_block_sizes() = {kPoseSize, kPoseSize, kPoseSize, kPlaneNormalSize, 1};
  set_num_residuals(2 * static_cast<int>(features_.size()) + (loss_ ? 1 : 0));
}

bool StackedHomographyResiduals::Evaluate(double const* const* x, double* residuals,
                                          double** jacobians) const {
  using PoseRows = Eigen::Map<Eigen::Matrix<double, 2, kPoseSize, Eigen::RowMajor>>;
  using NormalRows = Eigen::Map<Eigen::Matrix<double, 2, kPlaneNormalSize, Eigen::RowMajor>>;
  const TwoViewPoses poses(x[0], x[1], x[2]);
  const Eigen::Map<const Eigen::Vector3d> n_w(x[3]);
  const bool any = jacobians != nullptr;
  const auto wanted = [&](int k) { return any && jacobians[k]; };
  // Tangent → ambient (pose_manifold.h) of each pose block: J_a = J_t · lift.
  Eigen::Matrix<double, kPoseLocalSize, kPoseSize> lift[3];
  for (int k = 0; k < 3; ++k)
    if (wanted(k))
      lift[k] = tangentToAmbient<kPoseLocalSize>(
          Eigen::Matrix<double, kPoseLocalSize, kPoseLocalSize>::Identity(), x[k]);
  double cost_gap = 0;  // Σₖ ρ(sₖ) − |r'ₖ|²
  for (size_t f = 0; f < features_.size(); ++f) {
    TangentJacobian J[3];
    Eigen::Matrix<double, 2, 3> J_normal;
    Eigen::Vector2d r, J_distance;
    if (!homographyInTangent(poses, n_w, x[4][0], features_[f].u_i, features_[f].u_j, sqrt_info_, r,
                             wanted(0) ? &J[0] : nullptr, wanted(1) ? &J[1] : nullptr,
                             wanted(2) ? &J[2] : nullptr, wanted(3) ? &J_normal : nullptr,
                             wanted(4) ? &J_distance : nullptr))
      return false;
    if (loss_) {
      const RobustCorrection robust(*loss_, r.squaredNorm());
      for (int k = 0; k < 3; ++k)
        if (wanted(k)) robust.correctJacobian(r, J[k]);
      if (wanted(3)) robust.correctJacobian(r, J_normal);
      if (wanted(4)) robust.correctJacobian(r, J_distance);
      robust.correctResidual(r);
      cost_gap += robust.cost() - r.squaredNorm();
    }
    const int row = 2 * static_cast<int>(f);
    Eigen::Map<Eigen::Vector2d>{residuals + row} = r;
    if (!any) continue;
    for (int k = 0; k < 3; ++k)
      if (jacobians[k]) PoseRows(jacobians[k] + kPoseSize * row) = J[k] * lift[k];
    if (jacobians[3]) NormalRows(jacobians[3] + kPlaneNormalSize * row) = J_normal;
    if (jacobians[4]) Eigen::Map<Eigen::Vector2d>{jacobians[4] + row} = J_distance;
  }
  if (!loss_) return true;
  const int last = num_residuals() - 1;
  residuals[last] = std::sqrt(std::max(0.0, cost_gap));
  if (!any) return true;
  for (int k = 0; k < 5; ++k) {
    const int size = parameter_block_sizes()[k];
    if (jacobians[k]) std::fill_n(jacobians[k] + last * size, size, 0.0);
  }
  return true;
}

}  // namespace rpvio
