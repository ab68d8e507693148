#pragma once
// Random rigid transforms for the factor tests, and their pose blocks (parameter_blocks.h).
#include <Eigen/Geometry>
#include <random>
#include <vector>

namespace rpvio::test {

inline std::vector<double> poseBlock(const Eigen::Isometry3d& T) {
  const Eigen::Quaterniond q(T.linear());
  return {
      T.translation().x(), T.translation().y(), T.translation().z(), q.x(), q.y(), q.z(), q.w()};
}

/// A uniformly random rotation and a translation of `translation` m standard deviation per axis.
inline Eigen::Isometry3d randomPose(std::mt19937_64& rng, double translation) {
  std::normal_distribution<double> g(0, 1);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
  T.translation() = translation * Eigen::Vector3d(g(rng), g(rng), g(rng));
  return T;
}

}  // namespace rpvio::test
