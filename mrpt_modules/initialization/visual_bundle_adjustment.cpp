#include "mrpt_modules/initialization/visual_bundle_adjustment.h"

#include <ceres/ceres.h>
#include <ceres/sphere_manifold.h>

#include <array>

#include "mrpt_modules/factors/homography_factor.h"
#include "mrpt_modules/factors/pose_manifold.h"

namespace rpvio {
namespace {

/// Reprojection of a 3D point X_r into a camera [p_r_c, q_r_c]: u − π(R_r_cᵀ (X_r − p_r_c)).
struct PointReprojection {
  PointReprojection(const Eigen::Vector2d& u, double sqrt_info) : u(u), sqrt_info(sqrt_info) {}
  template <typename T>
  bool operator()(const T* camera, const T* X_r, T* residual) const {
    const RigidTransform<T> r_c = transformFromBlock(camera);
    const Eigen::Matrix<T, 3, 1> X_c =
        r_c.inverse().apply(Eigen::Matrix<T, 3, 1>(X_r[0], X_r[1], X_r[2]));
    residual[0] = T(sqrt_info) * (X_c.x() / X_c.z() - T(u.x()));
    residual[1] = T(sqrt_info) * (X_c.y() / X_c.z() - T(u.y()));
    return true;
  }
  Eigen::Vector2d u;
  double sqrt_info;
};

std::array<double, 7> toBlock(const CameraPose& c) {
  const Eigen::Quaterniond q(c.R_r_c);
  return {c.p_r_c.x(), c.p_r_c.y(), c.p_r_c.z(), q.x(), q.y(), q.z(), q.w()};
}

CameraPose fromBlock(const std::array<double, 7>& b) {
  const Eigen::Quaterniond q(b[6], b[3], b[4], b[5]);
  return {q.normalized().toRotationMatrix(), Eigen::Vector3d(b[0], b[1], b[2])};
}

double rmsPx(ceres::Problem& problem, double sqrt_info) {
  double cost = 0;
  ceres::Problem::EvaluateOptions options;
  options.apply_loss_function = false;
  std::vector<double> residuals;
  problem.Evaluate(options, &cost, &residuals, nullptr, nullptr);
  if (residuals.empty()) return 0;
  return std::sqrt(2 * cost / residuals.size()) * 460.0 / sqrt_info;
}

}  // namespace

BundleAdjustmentReport bundleAdjust(SfmWindow& window, const BundleAdjustmentGauge& gauge,
                                    const BundleAdjustmentOptions& options) {
  BundleAdjustmentReport report;
  std::vector<std::array<double, 7>> cameras(window.cameras.size());
  for (size_t k = 0; k < cameras.size(); ++k)
    if (window.cameras[k]) cameras[k] = toBlock(*window.cameras[k]);
  std::vector<std::array<double, 3>> points(window.tracks.size());
  std::map<int, std::array<double, 4>> planes;  // n (3), d (1)
  for (const auto& [id, p] : window.planes) planes[id] = {p.n.x(), p.n.y(), p.n.z(), p.d};
  std::array<double, 7> identity_mount = {0, 0, 0, 0, 0, 0, 1};

  ceres::Problem::Options problem_options;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  PoseManifold pose_manifold;
  ceres::SphereManifold<3> sphere;
  ceres::ProductManifold<ceres::SubsetManifold, ceres::EigenQuaternionManifold> rotation_only(
      ceres::SubsetManifold(3, {0, 1, 2}), ceres::EigenQuaternionManifold());
  ceres::CauchyLoss loss(options.cauchy_scale);
  for (size_t t = 0; t < window.tracks.size(); ++t) {
    const SfmTrack& track = window.tracks[t];
    size_t solved = 0;
    for (const auto& o : track.observations) solved += window.cameras[o.frame].has_value();
    if (track.X_r && solved >= 2) {
      points[t] = {track.X_r->x(), track.X_r->y(), track.X_r->z()};
      for (const auto& o : track.observations)
        if (window.cameras[o.frame])
          problem.AddResidualBlock(new ceres::AutoDiffCostFunction<PointReprojection, 2, 7, 3>(
                                       new PointReprojection(o.u, options.sqrt_info)),
                                   &loss, cameras[o.frame].data(), points[t].data());
    }
    const auto plane = planes.find(track.plane_id);
    if (!options.homography_residuals || plane == planes.end()) continue;
    const SfmObservation* previous = nullptr;
    for (const auto& o : track.observations) {
      if (!window.cameras[o.frame]) continue;
      if (previous)
        problem.AddResidualBlock(HomographyResidual::create(previous->u, o.u, options.sqrt_info),
                                 &loss, cameras[previous->frame].data(), cameras[o.frame].data(),
                                 identity_mount.data(), plane->second.data(),
                                 plane->second.data() + 3);
      previous = &o;
    }
  }
  for (auto& c : cameras)
    if (problem.HasParameterBlock(c.data())) problem.SetManifold(c.data(), &pose_manifold);
  for (auto& [id, p] : planes)
    if (problem.HasParameterBlock(p.data())) {
      problem.SetManifold(p.data(), &sphere);
      if (gauge.fixed_distance_plane == id) problem.SetParameterBlockConstant(p.data() + 3);
    }
  if (problem.HasParameterBlock(identity_mount.data()))
    problem.SetParameterBlockConstant(identity_mount.data());
  double* fixed = cameras.at(gauge.fixed_frame).data();
  if (problem.HasParameterBlock(fixed)) problem.SetParameterBlockConstant(fixed);
  if (gauge.fixed_position_frame) {
    double* block = cameras.at(*gauge.fixed_position_frame).data();
    if (problem.HasParameterBlock(block)) problem.SetManifold(block, &rotation_only);
  }
  report.residuals = static_cast<size_t>(problem.NumResidualBlocks());
  if (report.residuals == 0) return report;
  report.initial_rms_px = rmsPx(problem, options.sqrt_info);
  ceres::Solver::Options solver;
  solver.max_num_iterations = options.max_iterations;
  solver.linear_solver_type = ceres::DENSE_SCHUR;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  report.converged = summary.termination_type == ceres::CONVERGENCE;
  report.final_rms_px = rmsPx(problem, options.sqrt_info);
  for (size_t k = 0; k < cameras.size(); ++k)
    if (window.cameras[k]) window.cameras[k] = fromBlock(cameras[k]);
  for (size_t t = 0; t < window.tracks.size(); ++t)
    if (problem.HasParameterBlock(points[t].data()))
      window.tracks[t].X_r = Eigen::Vector3d(points[t].data());
  for (auto& [id, p] : planes) {
    window.planes[id].n = Eigen::Vector3d(p.data()).normalized();
    window.planes[id].d = p[3];
  }
  return report;
}

}  // namespace rpvio
