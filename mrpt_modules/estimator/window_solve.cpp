// SlidingWindowEstimator's solves (sliding_window_estimator.h): the window's factors (IMU,
// reprojection, stacked homographies, camera height, accelerometer-bias prior, the
// marginalization prior) in one Ceres problem, solved and, when due, the planes' covariances.
#include <ceres/ceres.h>

#include <map>

#include "mrpt_modules/estimator/estimator_problem.h"
#include "mrpt_modules/estimator/sliding_window_estimator.h"
#include "mrpt_modules/factors/accel_bias_prior_factor.h"
#include "mrpt_modules/factors/camera_height_factor.h"
#include "mrpt_modules/factors/imu_factor.h"
#include "mrpt_modules/factors/reprojection_factor.h"
#include "mrpt_modules/factors/stacked_homography_factor.h"

namespace rpvio {

void SlidingWindowEstimator::optimize(WindowSolve solve) {
  const size_t n = window_.size();
  // Between keyframes only the two newest frames move (the second newest is dropped after this
  // solve): a motion-only update against the rest of the window, its depths and planes held.
  const bool motion_only = solve == WindowSolve::kNewestFrames && n >= 3;
  const size_t first_free = motion_only ? n - 2 : 0;
  std::set<uint64_t> free_frames;
  for (size_t k = first_free; k < n; ++k) free_frames.insert(window_[k]->id);
  EstimatorProblem solve_problem(mount_, options_.cauchy_scale);
  ceres::Problem& problem = solve_problem.problem;
  for (size_t k = motion_only ? first_free - 1 : 0; k < n; ++k) {
    problem.AddParameterBlock(window_[k]->pose, 7, &solve_problem.pose_manifold);
    problem.AddParameterBlock(window_[k]->speed_bias, 9);
  }
  const Eigen::Vector3d g(0, 0, -calib_.imu.gravity);
  for (size_t k = std::max<size_t>(first_free, 1); k < n; ++k)
    problem.AddResidualBlock(new ImuFactor(window_[k]->imu_from_previous, g), nullptr,
                             window_[k - 1]->pose, window_[k - 1]->speed_bias, window_[k]->pose,
                             window_[k]->speed_bias);
  std::map<uint64_t, double*> pose_of;
  for (auto& f : window_) pose_of[f->id] = f->pose;
  const uint64_t newest = window_.back()->id;
  report_.features = 0;
  std::set<int> planes_with_factors;
  std::vector<double*> held;  // blocks the solve uses but does not move
  HomographyGroups homographies;
  const std::set<int> constrained = planes_.constrained(features_);
  for (auto& [id, track] : features_.tracks()) {
    if (!inUse(track)) continue;
    const TrackObservation& anchor = track.observations.front();
    PlaneEstimate* plane = planes_.homographyPlane(track, constrained);
    if (plane) planes_with_factors.insert(track.plane_id);
    if (track.observations.back().frame == newest) ++report_.features;
    const bool anchor_free = free_frames.count(anchor.frame) > 0;
    bool track_added = false;
    for (size_t k = 1; k < track.observations.size(); ++k) {
      const TrackObservation& o = track.observations[k];
      if (!anchor_free && !free_frames.count(o.frame)) continue;
      track_added = true;
      problem.AddResidualBlock(ReprojectionResidual::create(anchor.normalized, o.normalized,
                                                            trackWeight(track.plane_id)),
                               &solve_problem.loss, pose_of[anchor.frame], pose_of[o.frame], mount_,
                               track.inv_depth);
      if (plane)
        homographies[{track.plane_id, anchor.frame, o.frame}].push_back(
            {anchor.normalized, o.normalized});
    }
    if (motion_only && track_added) held.push_back(track.inv_depth);
  }
  for (auto& [key, features] : homographies) {
    const auto& [plane_id, frame_i, frame_j] = key;
    PlaneEstimate& plane = planes_.estimates().at(plane_id);
    problem.AddResidualBlock(new StackedHomographyResiduals(
                                 std::move(features), trackWeight(plane_id), &solve_problem.loss),
                             nullptr, pose_of[frame_i], pose_of[frame_j], mount_, plane.normal,
                             plane.distance);
  }
  report_.planes = planes_with_factors.size();
  if (prior_ &&
      (!motion_only || std::any_of(prior_->blocks.begin(), prior_->blocks.end(),
                                   [&](double* b) { return problem.HasParameterBlock(b); })))
    problem.AddResidualBlock(new MarginalizationFactor(prior_), nullptr, prior_->blocks);
  if (accel_bias_prior_ && !motion_only)
    problem.AddResidualBlock(accelBiasPriorFactor(), nullptr, window_.front()->speed_bias);
  ground_ = chooseGround(planes_with_factors);
  report_.ground_plane = ground_ ? ground_->plane : -1;
  if (ground_) {
    PlaneEstimate& ground = planes_.estimates().at(ground_->plane);
    for (size_t k = first_free; k < n; ++k)
      problem.AddResidualBlock(cameraHeightFactor(), nullptr, window_[k]->pose, mount_,
                               ground.normal, ground.distance);
  }
  std::vector<double*> held_planes;
  for (auto& [mask, e] : planes_.estimates()) {
    if (!problem.HasParameterBlock(e.normal)) continue;
    problem.SetManifold(e.normal, &solve_problem.sphere);
    // A plane in the prior only because its tracks in use fell below kMinPlanePoints is held: the
    // prior alone, linearized where the plane was, does not bound it (seed 2 C1: a crate face
    // walked 180° in 1.5 s, on 4–9 tracks). A well-tracked plane without factors (rpvio-single's
    // other planes) stays free: holding those biased rpvio-single (seed 1 C8 0.041 -> 0.063 m).
    if (motion_only || !constrained.count(mask))
      held_planes.insert(held_planes.end(), {e.normal, e.distance});
  }
  for (double* block : held_planes) problem.SetParameterBlockConstant(block);
  for (double* block : held) problem.SetParameterBlockConstant(block);
  for (size_t k = 0; k < first_free; ++k)
    for (double* block : {window_[k]->pose, window_[k]->speed_bias})
      if (problem.HasParameterBlock(block)) problem.SetParameterBlockConstant(block);
  // Gauge: the window cannot observe its yaw and position, so the oldest frame keeps them. Left
  // free, each solve moved the window along them by what the prior's linearization lends them
  // (degrees of yaw within a second on the simulator). Its tilt stays free, with or without a
  // prior: the IMU factors observe it. Held until the first marginalization, it kept the
  // initializer's gravity, which the accelerometer bias tilts (0.36 deg on seed-1 C1, the
  // horizontal bias over g); freed all at once there, the window turned by 0.1-0.2 deg and its
  // newest frame jumped 1-2 cm (7 cm on hard MP).
  if (!motion_only) problem.SetManifold(window_.front()->pose, &solve_problem.gauge_manifold);

  if (solve != WindowSolve::kPlaneCovariances) {
    ceres::Solver::Options solver;
    solver.trust_region_strategy_type = ceres::DOGLEG;
    solver.linear_solver_type = ceres::DENSE_SCHUR;
    solver.max_num_iterations = options_.max_iterations;
    if (options_.max_solver_time_s > 0)
      solver.max_solver_time_in_seconds = options_.max_solver_time_s;
    solver.num_threads = 1;
    ceres::Solver::Summary summary;
    ceres::Solve(solver, &problem, &summary);
    if (solve != WindowSolve::kWindowAndPlaneCovariances) return;
    // A long solve, or one whose planes' covariances are due (defer_plane_covariances), leaves
    // the covariances (if due) and the marginalization that follow it to the next frame
    // (summary.iterations counts the starting point too).
    const int iterations = static_cast<int>(summary.iterations.size()) - 1;
    const bool covariances_to_compute = covariancesDue() && !planes_with_factors.empty();
    keyframe_work_deferred_ = iterations > options_.max_iterations_before_deferring ||
                              (covariances_to_compute && options_.defer_plane_covariances);
    if (keyframe_work_deferred_ || !covariances_to_compute) return;
  }
  // The covariances count the held planes' uncertainty (what the prior knows of them): held, they
  // would be taken as exact and the others' sigmas shrink (a wall's offset 0.16 -> 0.05 m, for an
  // error of 0.17 m, EstimatorOnSimulator.PlaneMapCovariancesAreConsistent).
  for (double* block : held_planes) problem.SetParameterBlockVariable(block);
  // Not computed (no plane with factors, or not evaluable): due again on the next keyframe.
  if (!planes_.updateCovariances(problem, planes_with_factors)) return;
  keyframes_since_covariances_ = 0;
  ++covariance_updates_;
}

double SlidingWindowEstimator::trackWeight(int plane_id) const {
  return options_.virtual_focal /
         (plane_id == kGroundLabel ? options_.ground_pixel_sigma : options_.pixel_sigma);
}

std::optional<GroundInWindow> SlidingWindowEstimator::chooseGround(
    const std::set<int>& planes) const {
  if (calib_.camera_height <= 0 || options_.camera_height_sigma <= 0) return std::nullopt;
  const Eigen::Vector3d newest_camera = camera(window_.back()->id).translation();
  return groundInWindow(planes_.estimates(), planes, newest_camera, calib_.camera_height,
                        options_.initializerOptions().max_ground_tilt_deg);
}

ceres::CostFunction* SlidingWindowEstimator::accelBiasPriorFactor() const {
  return new AccelBiasPriorResidual(*accel_bias_prior_, options_.accel_bias_prior_sigma);
}

ceres::CostFunction* SlidingWindowEstimator::cameraHeightFactor() const {
  return CameraHeightResidual::create(calib_.camera_height, ground_->side,
                                      1 / options_.camera_height_sigma);
}

}  // namespace rpvio
