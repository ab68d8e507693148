#pragma once
// Marginal covariance of a few parameter blocks of a solved Ceres problem: the inverse of the
// Gauss–Newton information JᵀJ at the current values (robust losses applied), every other free
// block marginalized. ceres::Covariance does the same with a sparse QR of the whole Jacobian
// (21 ms per sliding window here); the blocks of one tangent number (a window's hundreds of inverse
// depths) are eliminated here by their Schur complement first, so only the rest is dense.
#include <ceres/problem.h>
#include <Eigen/Core>
#include <optional>
#include <vector>

namespace rpvio {

/// Joint covariance of `wanted` (free blocks of `problem`) in tangent coordinates, the blocks'
/// coordinates concatenated in the order given. A direction the information leaves free (an
/// unobserved block, a free gauge) gets an enormous variance (10¹² times its block's scale);
/// std::nullopt when the Jacobian cannot be evaluated.
std::optional<Eigen::MatrixXd> marginalCovariance(ceres::Problem& problem,
                                                  const std::vector<double*>& wanted);

}  // namespace rpvio
