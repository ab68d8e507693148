// The gauge manifold of the window's oldest pose (pose_manifold.h): Ceres' manifold invariants
// (Plus/Minus inverse of each other, Plus and Minus Jacobians against numeric differentiation),
// and that no step moves the position or the yaw.
#include <ceres/manifold_test_utils.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "mrpt_modules/factors/parameter_blocks.h"
#include "mrpt_modules/factors/pose_manifold.h"

namespace rpvio {
namespace {

Eigen::Matrix<double, 7, 1> pose(const Eigen::Vector3d& p, const Eigen::Quaterniond& q) {
  Eigen::Matrix<double, 7, 1> x;
  x << p, q.x(), q.y(), q.z(), q.w();
  return x;
}

TEST(TiltOnlyPoseManifold, CeresManifoldInvariantsHold) {
  using namespace ceres;  // the invariants' matchers
  const TiltOnlyPoseManifold manifold;
  for (const Eigen::Quaterniond& q :
       {Eigen::Quaterniond(0.9, 0.1, -0.3, 0.2).normalized(), Eigen::Quaterniond::Identity(),
        Eigen::Quaterniond(Eigen::AngleAxisd(2.5, Eigen::Vector3d(0.2, 0.1, 1).normalized()))}) {
    const Vector x = pose({1, -2, 3}, q);
    const Vector delta = Eigen::Vector2d(0.05, -0.03);
    Vector y(7);
    manifold.Plus(x.data(), Eigen::Vector2d(-0.02, 0.04).data(), y.data());
    EXPECT_THAT_MANIFOLD_INVARIANTS_HOLD(manifold, x, delta, y, 1e-9);
  }
}

TEST(TiltOnlyPoseManifold, StepsKeepPositionAndYaw) {
  const TiltOnlyPoseManifold manifold;
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitX()));
  const auto x = pose({4, 5, 6}, q);
  const double delta[2] = {0.3, -0.2};
  double y[7];
  manifold.Plus(x.data(), delta, y);
  EXPECT_EQ(posePosition(y), posePosition(x.data()));
  // The step is a rotation about a horizontal world axis: its axis has no z component.
  const Eigen::AngleAxisd step(poseRotation(y) * poseRotation(x.data()).conjugate());
  EXPECT_NEAR(step.angle(), std::hypot(0.3, 0.2), 1e-12);
  EXPECT_NEAR(step.axis().z(), 0, 1e-12);
}

}  // namespace
}  // namespace rpvio
