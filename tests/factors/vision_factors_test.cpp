// Reprojection and homography factors on the simulator's geometry: zero on the truth (the
// factors' conventions are the simulator's); the reprojection factor's Jacobians against central
// differences on the manifolds (the homography factor's: homography_factor_test.cpp).
#include <gtest/gtest.h>

#include <ceres/manifold.h>

#include "mrpt_modules/factors/homography_factor.h"
#include "mrpt_modules/factors/pose_manifold.h"
#include "mrpt_modules/factors/reprojection_factor.h"
#include "sim/simulator.h"
#include "tests/factors/jacobian_check.h"

namespace rpvio {
namespace {

std::vector<double> block(const Eigen::Isometry3d& T) {
  const Eigen::Quaterniond q(T.linear());
  return {
      T.translation().x(), T.translation().y(), T.translation().z(), q.x(), q.y(), q.z(), q.w()};
}

struct TwoViews {
  const sim::SimConfig config;
  sim::Simulator sim{config};
  double ti = 10.0, tj = 10.5;
  std::vector<double> pose_i = block(sim.bodyPose(ti)), pose_j = block(sim.bodyPose(tj));
  std::vector<double> mount = block(sim.config().camera.T_BC());
  Eigen::Vector2d normalized(double t, const Eigen::Vector3d& X) {
    const Eigen::Vector3d c = sim.cameraPose(t).inverse() * X;
    return c.head<2>() / c.z();
  }
};

TEST(ReprojectionFactor, ZeroOnTruthAndJacobiansMatchNumeric) {
  TwoViews v;
  const sim::SceneHit hit = v.sim.castPixel(v.ti, 300.2, 250.7);
  const Eigen::Vector3d X = hit.point;
  const double depth = (v.sim.cameraPose(v.ti).inverse() * X).z();
  std::unique_ptr<ceres::CostFunction> f(
      ReprojectionResidual::create(v.normalized(v.ti, X), v.normalized(v.tj, X), 320 / 1.5));
  std::vector<std::vector<double>> x = {v.pose_i, v.pose_j, v.mount, {1.0 / depth}};
  double r[2];
  std::vector<const double*> p = {x[0].data(), x[1].data(), x[2].data(), x[3].data()};
  f->Evaluate(p.data(), r, nullptr);
  EXPECT_LT(std::hypot(r[0], r[1]), 1e-6);
  x[3][0] *= 1.3;  // off the truth
  x[1][0] += 0.2;
  const PoseManifold pm;
  const double worst = test::worstJacobianError(*f, x, {&pm, &pm, &pm, nullptr});
  std::printf("reprojection factor: worst Jacobian error %.2e\n", worst);
  EXPECT_LT(worst, 1e-6);
}

TEST(HomographyFactor, ZeroOnTheSimulatorsTruePlane) {
  TwoViews v;
  const sim::SceneHit hit = v.sim.castPixel(v.ti, 420.0, 200.0);
  const sim::ScenePlane* plane = v.sim.scene().plane(hit.label);
  ASSERT_NE(plane, nullptr);
  std::unique_ptr<ceres::CostFunction> f(HomographyResidual::create(
      v.normalized(v.ti, hit.point), v.normalized(v.tj, hit.point), 320 / 1.5));
  std::vector<std::vector<double>> x = {v.pose_i,
                                        v.pose_j,
                                        v.mount,
                                        {plane->normal.x(), plane->normal.y(), plane->normal.z()},
                                        {plane->distance()}};
  double r[2];
  std::vector<const double*> p = {x[0].data(), x[1].data(), x[2].data(), x[3].data(), x[4].data()};
  f->Evaluate(p.data(), r, nullptr);
  EXPECT_LT(std::hypot(r[0], r[1]), 1e-6) << "plane " << hit.label;
  // The plane 0.7 m off: the prediction moves (by 0.15 pixel sigmas for this far wall).
  x[4][0] += 0.7;
  f->Evaluate(p.data(), r, nullptr);
  EXPECT_GT(std::hypot(r[0], r[1]), 0.05) << "plane " << hit.label;
}

}  // namespace
}  // namespace rpvio
