#pragma once
// A Ceres problem over the estimator's parameter blocks (parameter_blocks.h) with the manifolds
// and the robust loss its solves share (borrowed, not owned), and the camera mount added constant.
#include <ceres/ceres.h>
#include <ceres/sphere_manifold.h>

#include <memory>
#include <vector>

#include "mrpt_modules/factors/pose_manifold.h"

namespace rpvio {

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

  /// The Schur ordering that eliminates `depths` (the tracks' inverse depths) and keeps every
  /// other block in the reduced system. Left to Ceres, the eliminated independent set also took
  /// IMU speed/bias blocks, whose elimination fills the reduced system: the batch refinement of
  /// an 80 s sequence factored it 3x slower (C4 rpvio-single: 17.4 s against 5.8 s).
  std::shared_ptr<ceres::ParameterBlockOrdering> depthsEliminated(
      const std::vector<double*>& depths) const {
    auto ordering = std::make_shared<ceres::ParameterBlockOrdering>();
    for (double* depth : depths) ordering->AddElementToGroup(depth, 0);
    std::vector<double*> blocks;
    problem.GetParameterBlocks(&blocks);
    for (double* block : blocks)
      if (!ordering->IsMember(block)) ordering->AddElementToGroup(block, 1);
    return ordering;
  }

 private:
  static ceres::Problem::Options options() {
    ceres::Problem::Options o;
    o.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    o.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    return o;
  }
};

}  // namespace rpvio
