#pragma once
// A Ceres problem over the estimator's parameter blocks (parameter_blocks.h) with the manifolds
// and the robust loss its solves share (borrowed, not owned), and the camera mount added constant.
#include <ceres/ceres.h>
#include <ceres/sphere_manifold.h>

#include <map>
#include <tuple>
#include <vector>

#include "mrpt_modules/factors/pose_manifold.h"
#include "mrpt_modules/factors/stacked_homography_factor.h"

namespace rpvio {

/// The homography factors' features by plane, anchor frame and frame: one block each
/// (stacked_homography_factor.h).
using HomographyGroups =
    std::map<std::tuple<int, uint64_t, uint64_t>, std::vector<StackedHomographyResiduals::Feature>>;

struct EstimatorProblem {
  EstimatorProblem(double* mount, double cauchy_scale) : loss(cauchy_scale), problem(options()) {
    problem.AddParameterBlock(mount, 7, &pose_manifold);
    problem.SetParameterBlockConstant(mount);
  }

  PoseManifold pose_manifold;
  TiltOnlyPoseManifold gauge_manifold;  // position and yaw held
  ceres::SphereManifold<3> sphere;      // plane normals
  ceres::CauchyLoss loss;               // on the reprojection and homography factors
  ceres::Problem problem;               // declared last: destroyed before what it borrows

 private:
  static ceres::Problem::Options options() {
    ceres::Problem::Options o;
    o.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    o.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    return o;
  }
};

}  // namespace rpvio
