#include "mrpt_modules/estimator/sliding_window_estimator.h"

#include <ceres/ceres.h>
#include <Eigen/Dense>
#include <chrono>
#include <cmath>
#include <map>
#include <tuple>

#include "mrpt_modules/estimator/batch_refinement.h"
#include "mrpt_modules/estimator/estimator_problem.h"
#include "mrpt_modules/factors/accel_bias_prior_factor.h"
#include "mrpt_modules/factors/camera_height_factor.h"
#include "mrpt_modules/factors/imu_factor.h"
#include "mrpt_modules/factors/parameter_blocks.h"
#include "mrpt_modules/factors/pose_manifold.h"
#include "mrpt_modules/factors/reprojection_factor.h"
#include "mrpt_modules/factors/stacked_homography_factor.h"
#include "mrpt_modules/frontend/feature_tracker.h"
#include "mrpt_modules/initialization/time_offset.h"

namespace rpvio {
namespace {

constexpr double kMinDepth = 0.1, kMaxDepth = 100;

/// The homography factors' features by plane, anchor frame and frame: one block each
/// (stacked_homography_factor.h).
using HomographyGroups =
    std::map<std::tuple<int, uint64_t, uint64_t>, std::vector<StackedHomographyResiduals::Feature>>;

/// The noise densities and random walks of `noise` times `factor`.
ImuNoise inflatedNoise(ImuNoise noise, double factor) {
  for (double* density : {&noise.accel_noise_density, &noise.gyro_noise_density,
                          &noise.accel_random_walk, &noise.gyro_random_walk})
    *density *= factor;
  return noise;
}

}  // namespace

SlidingWindowEstimator::SlidingWindowEstimator(const Calibration& calibration,
                                               const EstimatorOptions& options, MapSink& map)
    : calib_(calibration),
      options_(options),
      imu_link_(inflatedNoise(calibration.imu, options.imu_noise_inflation),
                calibration.imu.gravity, options.imuLinkOptions()),
      bootstrapper_(calibration, options, imu_link_),
      planes_(options.homography_planes),
      plane_verifier_(options.planeVerifierOptions()),
      plane_discovery_(options.planeDiscoveryOptions()),
      map_(map) {
  setPoseBlock(calib_.T_BC, mount_);
  // While initializing, the labels discovered since and the planes rejected since reach back
  // over the buffered frames.
  if (options_.discover_planes)
    bootstrapper_.setFrameScreen([this](const FeatureFrame& f) { return screenedNow(f); });
}

FeatureFrame SlidingWindowEstimator::screenedNow(const FeatureFrame& frame) const {
  return plane_verifier_.withoutRejected(options_.discover_planes ? plane_discovery_.labelled(frame)
                                                                  : frame);
}

Eigen::Isometry3d SlidingWindowEstimator::camera(uint64_t frame_id) const {
  for (const auto& f : window_)
    if (f->id == frame_id) return poseIsometry(f->pose) * calib_.T_BC;
  return Eigen::Isometry3d::Identity();  // not reached: tracks only reference window frames
}

CameraPoseLookup SlidingWindowEstimator::cameraLookup() const {
  return [this](uint64_t id) { return camera(id); };
}

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
  const double weight = options_.virtual_focal / options_.pixel_sigma;
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
      problem.AddResidualBlock(
          ReprojectionResidual::create(anchor.normalized, o.normalized, weight),
          &solve_problem.loss, pose_of[anchor.frame], pose_of[o.frame], mount_, track.inv_depth);
      if (plane)
        homographies[{track.plane_id, anchor.frame, o.frame}].push_back(
            {anchor.normalized, o.normalized});
    }
    if (motion_only && track_added) held.push_back(track.inv_depth);
  }
  for (auto& [key, features] : homographies) {
    const auto& [plane_id, frame_i, frame_j] = key;
    PlaneEstimate& plane = planes_.estimates().at(plane_id);
    problem.AddResidualBlock(
        new StackedHomographyResiduals(std::move(features), weight, &solve_problem.loss), nullptr,
        pose_of[frame_i], pose_of[frame_j], mount_, plane.normal, plane.distance);
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

void SlidingWindowEstimator::rejectDepthOutliers() {
  for (auto& [id, track] : features_.tracks())
    if (track.triangulated &&
        (track.inv_depth[0] < 1.0 / kMaxDepth || track.inv_depth[0] > 1.0 / kMinDepth))
      features_.untriangulate(track);
}

std::string SlidingWindowEstimator::failure(const double* predicted_pose) const {
  const Frame& f = *window_.back();
  for (double x : f.pose)
    if (!std::isfinite(x)) return "non-finite state";
  for (double x : f.speed_bias)
    if (!std::isfinite(x)) return "non-finite state";
  if (Eigen::Vector3d(f.speed_bias + 3).norm() > options_.max_accel_bias)
    return "implausible accelerometer bias";
  if (Eigen::Vector3d(f.speed_bias + 6).norm() > options_.max_gyro_bias)
    return "implausible gyroscope bias";
  if ((posePosition(f.pose) - posePosition(predicted_pose)).norm() > options_.max_jump_m)
    return "position jump";
  if (poseRotation(f.pose).angularDistance(poseRotation(predicted_pose)) * 180 / M_PI >
      options_.max_jump_deg)
    return "rotation jump";
  if (f.features.t - last_seen_features_t_ > options_.max_blind_s) return "too few features";
  return "";
}

bool SlidingWindowEstimator::secondNewestIsKeyframe() const {
  const size_t n = window_.size();
  if (n < 3) return true;
  const FeatureFrame& previous_kf = window_[n - 3]->features;
  const FeatureFrame& candidate = window_[n - 2]->features;
  return averageParallax(previous_kf, candidate, options_.virtual_focal) >=
             options_.keyframe_parallax_px ||
         commonFeatures(previous_kf, candidate) < options_.keyframe_min_tracks ||
         candidate.t - previous_kf.t >= options_.max_keyframe_gap_s;
}

void SlidingWindowEstimator::marginalizeOldest() {
  Frame& oldest = *window_.front();
  Frame& next = *window_[1];
  Marginalizer marginalizer;
  marginalizer.setConstant(mount_);
  if (prior_)
    marginalizer.addFactor(std::make_unique<MarginalizationFactor>(prior_), nullptr,
                           prior_->blocks);
  const Eigen::Vector3d g(0, 0, -calib_.imu.gravity);
  // An IMU factor over a gap or saturated samples is left out of the prior: its model error,
  // frozen by the linearization, pulled the accelerometer bias away within a second (the
  // simulated 0.2 s gap ended in a reset).
  const bool imu_linked = !imu_link_.defects(next.imu, oldest.features.t, next.features.t).any();
  if (imu_linked)
    marginalizer.addFactor(std::make_unique<ImuFactor>(next.imu_from_previous, g), nullptr,
                           {oldest.pose, oldest.speed_bias, next.pose, next.speed_bias});
  std::set<const double*> remove = {oldest.pose, oldest.speed_bias};
  std::map<uint64_t, double*> pose_of;
  for (auto& f : window_) pose_of[f->id] = f->pose;
  const double weight = options_.virtual_focal / options_.pixel_sigma;
  auto loss = std::make_shared<ceres::CauchyLoss>(options_.cauchy_scale);
  const std::set<int> constrained = planes_.constrained(features_);
  HomographyGroups homographies;
  for (auto& [id, track] : features_.tracks()) {
    if (!inUse(track) || track.observations.front().frame != oldest.id) continue;
    const TrackObservation& anchor = track.observations.front();
    PlaneEstimate* plane = planes_.homographyPlane(track, constrained);
    for (size_t k = 1; k < track.observations.size(); ++k) {
      const TrackObservation& o = track.observations[k];
      marginalizer.addFactor(std::unique_ptr<ceres::CostFunction>(ReprojectionResidual::create(
                                 anchor.normalized, o.normalized, weight)),
                             loss, {oldest.pose, pose_of[o.frame], mount_, track.inv_depth});
      if (plane)
        homographies[{track.plane_id, anchor.frame, o.frame}].push_back(
            {anchor.normalized, o.normalized});
    }
    remove.insert(track.inv_depth);
  }
  // The planes stay states: what this keyframe's homographies knew of them stays in the prior.
  for (auto& [key, features] : homographies) {
    const auto& [plane_id, frame_i, frame_j] = key;
    PlaneEstimate& plane = planes_.estimates().at(plane_id);
    marginalizer.addFactor(
        std::make_unique<StackedHomographyResiduals>(std::move(features), weight, loss.get()),
        nullptr, {oldest.pose, pose_of[frame_j], mount_, plane.normal, plane.distance});
  }
  if (accel_bias_prior_) {
    marginalizer.addFactor(std::unique_ptr<ceres::CostFunction>(accelBiasPriorFactor()), nullptr,
                           {oldest.speed_bias});
    accel_bias_prior_.reset();
  }
  // The oldest keyframe's height above the ground stays in the prior with the ground plane.
  if (ground_) {
    PlaneEstimate& ground = planes_.estimates().at(ground_->plane);  // optimize() just used it
    marginalizer.addFactor(std::unique_ptr<ceres::CostFunction>(cameraHeightFactor()), nullptr,
                           {oldest.pose, mount_, ground.normal, ground.distance});
  }
  prior_ = marginalizer.marginalize(remove);
  flushPlanes();
  archiveKeyframe(oldest, imu_linked ? &next : nullptr);
  features_.removeFrame(oldest.id, cameraLookup());
  window_.pop_front();
  window_.front()->imu_from_previous = nullptr;
  window_.front()->imu.clear();
  forgetUnseenPlanes();
}

void SlidingWindowEstimator::forgetUnseenPlanes() {
  // Planes no longer seen live on in the map only: marginalized out of the prior, then dropped.
  std::set<int> seen;
  for (const auto& [id, track] : features_.tracks()) seen.insert(track.plane_id);
  std::set<const double*> gone;
  PlaneEstimates& planes = planes_.estimates();
  for (auto& [mask, e] : planes)
    if (!seen.count(mask) && prior_ && prior_->involves(e.normal))
      gone.insert({e.normal, e.distance});
  if (!gone.empty()) {
    Marginalizer marginalizer;
    marginalizer.addFactor(std::make_unique<MarginalizationFactor>(prior_), nullptr,
                           prior_->blocks);
    prior_ = marginalizer.marginalize(gone);
  }
  for (auto it = planes.begin(); it != planes.end();)
    it = seen.count(it->first) ? std::next(it) : planes.erase(it);
}

void SlidingWindowEstimator::dropSecondNewest() {
  const size_t n = window_.size();
  Frame& dropped = *window_[n - 2];
  Frame& newest = *window_[n - 1];
  const Frame& before = *window_[n - 3];
  if (prior_ && (prior_->involves(dropped.pose) || prior_->involves(dropped.speed_bias))) {
    Marginalizer marginalizer;
    marginalizer.addFactor(std::make_unique<MarginalizationFactor>(prior_), nullptr,
                           prior_->blocks);
    prior_ = marginalizer.marginalize({dropped.pose, dropped.speed_bias});
  }
  std::vector<ImuSample> merged = dropped.imu;
  appendSamples(merged, newest.imu);
  newest.imu = merged;
  newest.imu_from_previous =
      imu_link_.preintegrate(merged, before.features.t, newest.features.t, before.speed_bias);
  features_.removeFrame(dropped.id, cameraLookup());
  window_.erase(window_.end() - 2);
}

void SlidingWindowEstimator::flushPlanes() {
  const double t = window_.back()->features.t;
  PlanesSeen seen{planes_.observations(features_, cameraLookup(), t)};
  if (options_.map_all_planes) {
    const auto fitted = planes_.fittedObservations(
        features_, cameraLookup(), t, camera(window_.back()->id).translation(),
        options_.verify_planes ? &plane_verifier_.judgedStatic() : nullptr);
    seen.planes.insert(seen.planes.end(), fitted.begin(), fitted.end());
  }
  map_.planesSeen(seen);
}

void SlidingWindowEstimator::archiveKeyframe(const Frame& frame, const Frame* next) {
  KeyframeLeft left;
  ArchivedKeyframe& k = left.keyframe;
  k.id = frame.id;
  k.t = frame.features.t;
  std::copy(frame.pose, frame.pose + 7, k.pose);
  std::copy(frame.speed_bias, frame.speed_bias + 9, k.speed_bias);
  // The window's factor, noise inflated (with the calibration's noise the refined trajectories of
  // the simulated static sequences were 1.0-2.3x worse).
  if (next) k.to_next = next->imu_from_previous;
  left.observations = keyframeObservations(frame.id, features_, inUse);
  map_.keyframeLeft(left);
}

bool SlidingWindowEstimator::finishKeyframeWork() {
  if (!keyframe_work_deferred_) return false;
  keyframe_work_deferred_ = false;
  if (covariancesDue()) optimize(WindowSolve::kPlaneCovariances);
  marginalizeOldest();
  return true;
}

void SlidingWindowEstimator::finishMap() {
  finishKeyframeWork();
  if (initialized_) {
    // The last visit of each plane is handed over with covariances of the final window.
    if (keyframes_since_covariances_ > 0) optimize(WindowSolve::kPlaneCovariances);
    flushPlanes();
    for (size_t k = 0; k < window_.size(); ++k) {
      const bool linked =
          k + 1 < window_.size() &&
          !imu_link_
               .defects(window_[k + 1]->imu, window_[k]->features.t, window_[k + 1]->features.t)
               .any();
      archiveKeyframe(*window_[k], linked ? window_[k + 1].get() : nullptr);
    }
  }
  // The batch refinement weighs its factors as the window does.
  WindowFinished end;
  end.refinement.weight = options_.virtual_focal / options_.pixel_sigma;
  end.refinement.cauchy_scale = options_.cauchy_scale;
  end.refinement.gravity = calib_.imu.gravity;
  end.refinement.min_parallax_rad = options_.min_triangulation_angle_deg * M_PI / 180;
  end.refinement.min_plane_tracks = kMinPlanePoints;
  std::copy(mount_, mount_ + 7, end.mount);
  map_.windowFinished(end);
}

void SlidingWindowEstimator::startWindow(const InitializedWindow& init) {
  window_.clear();
  features_.clear();
  prior_.reset();
  for (const auto& keyframe : init.keyframes) {
    auto f = std::make_unique<Frame>();
    f->id = next_frame_id_++;
    f->features = keyframe.features;
    std::copy(keyframe.pose, keyframe.pose + 7, f->pose);
    std::copy(keyframe.speed_bias, keyframe.speed_bias + 9, f->speed_bias);
    if (!window_.empty()) {
      f->imu = keyframe.imu;
      f->imu_from_previous =
          imu_link_.preintegrate(f->imu, window_.back()->features.t, f->features.t, f->speed_bias);
    }
    features_.addFrame(f->id, f->features);
    window_.push_back(std::move(f));
  }
  // The initializer's points at the depths of this window's anchors.
  for (auto& [id, track] : features_.tracks()) {
    const auto point = init.points.find(id);
    if (point == init.points.end()) continue;
    const Eigen::Vector3d X_c = camera(track.observations.front().frame).inverse() * point->second;
    if (X_c.z() < kMinDepth || X_c.z() > kMaxDepth) continue;
    track.inv_depth[0] = 1.0 / X_c.z();
    track.triangulated = true;
  }
  planes_.start(init.planes);
  if (options_.accel_bias_prior_sigma > 0)
    accel_bias_prior_ = Eigen::Vector3d(window_.front()->speed_bias + 3);
  // Re-initialized soon enough after a reset: into the old world; else a new world, and the
  // archived keyframes are in another one.
  if (const auto shift =
          bootstrapper_.reconnect(window_.front()->features.t, window_.front()->pose))
    moveWindow(*shift);
  else
    map_.newWorld();
  initialized_ = true;
  last_seen_features_t_ = window_.back()->features.t;
  planes_.choose(features_, homographyEligible());
  features_.triangulate(cameraLookup(), options_.min_triangulation_angle_deg * M_PI / 180,
                        kMinDepth, kMaxDepth);
  // The planes the window already triangulates, as after every later frame: the first solve with
  // their homography factors, not the second (a discovered floor entering at the second moved the
  // scale by 0.24% at once, seed-1 C6).
  planes_.initialize(features_, cameraLookup(), camera(window_.back()->id).translation(),
                     map_.planesMap());
  optimize(WindowSolve::kWindow);
  rejectDepthOutliers();
}

void SlidingWindowEstimator::moveWindow(const WorldShift& s) {
  for (auto& f : window_) {
    const Eigen::Vector3d p = s.yaw * posePosition(f->pose) + s.shift;
    const Eigen::Quaterniond q = (s.yaw * poseRotation(f->pose)).normalized();
    const Eigen::Vector3d v = s.yaw * Eigen::Vector3d(f->speed_bias);
    const double pose[7] = {p.x(), p.y(), p.z(), q.x(), q.y(), q.z(), q.w()};
    std::copy(pose, pose + 7, f->pose);
    std::copy(v.data(), v.data() + 3, f->speed_bias);
  }
  for (auto& [mask, e] : planes_.estimates()) {
    const Eigen::Vector3d n = s.yaw * Eigen::Vector3d(e.normal);
    std::copy(n.data(), n.data() + 3, e.normal);
    e.distance[0] += n.dot(s.shift);
  }
}

void SlidingWindowEstimator::reset(const std::string& cause,
                                   const std::vector<ImuSample>& imu_since_good) {
  reset_log_.push_back({window_.empty() ? 0 : window_.back()->features.t, cause});
  status_ = "reset: " + cause;
  status_detail_ = status_;
  report_.state = "reset";
  initialized_ = false;
  keyframe_work_deferred_ = false;  // the window it was for is dropped
  keyframes_since_covariances_ = 0;
  map_.chainBroken();  // the window's frames, the link's other end, are dropped
  window_.clear();
  features_.clear();
  prior_.reset();
  accel_bias_prior_.reset();
  planes_.clear();
  ground_.reset();
  bootstrapper_.restart(imu_since_good, status_);
}

std::optional<Eigen::Quaterniond> SlidingWindowEstimator::rotationSincePreviousFrame(
    double t, const std::vector<ImuSample>& imu) {
  static const double kNoBias[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  // A corrected time offset moved this frame's time against the previous one's: start again.
  const bool same_clock = screened_offset_ == bootstrapper_.timeOffset();
  screened_offset_ = bootstrapper_.timeOffset();
  std::optional<Eigen::Quaterniond> rotation;
  if (const auto pre =
          screened_until_t_ < 0 || !same_clock
              ? nullptr
              : imu_link_.preintegrate(imu, screened_until_t_, t,
                                       initialized_ ? window_.back()->speed_bias : kNoBias)) {
    const Eigen::Quaterniond q_BC(calib_.T_BC.linear());
    rotation = q_BC.inverse() * pre->deltaQ() * q_BC;
  }
  screened_until_t_ = t;
  return rotation;
}

void SlidingWindowEstimator::dropPlaneFromWindow(int plane_id) {
  auto& tracks = features_.tracks();
  for (auto it = tracks.begin(); it != tracks.end();)
    it = it->second.plane_id == plane_id ? tracks.erase(it) : std::next(it);
}

FeatureFrame SlidingWindowEstimator::screenPlanes(const FeatureFrame& frame,
                                                  const std::vector<ImuSample>& imu) {
  if (!options_.verify_planes && !options_.discover_planes) return frame;
  const auto rotation = rotationSincePreviousFrame(frame.t, imu);
  const size_t known_rejections = plane_verifier_.rejections().size();
  const size_t known_discoveries = plane_discovery_.events().size();
  FeatureFrame kept = options_.discover_planes ? plane_discovery_.label(frame, rotation) : frame;
  kept = plane_verifier_.filter(kept, rotation);
  std::vector<int> dropped;
  for (size_t i = known_rejections; i < plane_verifier_.rejections().size(); ++i)
    dropped.push_back(plane_verifier_.rejections()[i].plane_id);
  for (size_t i = known_discoveries; i < plane_discovery_.events().size(); ++i)
    if (!plane_discovery_.events()[i].accepted)
      dropped.push_back(plane_discovery_.events()[i].plane_id);
  for (const int plane : dropped) dropPlaneFromWindow(plane);
  if (initialized_ && !dropped.empty()) forgetUnseenPlanes();
  return kept;
}

std::vector<StateEstimate> SlidingWindowEstimator::addFrame(
    const FeatureFrame& camera_frame, const std::vector<ImuSample>& imu_since_previous) {
  const auto start = std::chrono::steady_clock::now();       // the screening's time is counted too
  const bool finished_keyframe_work = finishKeyframeWork();  // on the window as it was left
  const FeatureFrame frame = screenPlanes(camera_frame, imu_since_previous);
  // While initializing, discovered labels reach back over the buffered frames (setFrameScreen).
  const FeatureFrame& to_bootstrapper = options_.discover_planes ? camera_frame : frame;
  auto elapsed_ms = [&] {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
  };
  report_ = FrameReport{};
  report_.finished_keyframe_work = finished_keyframe_work;
  std::vector<StateEstimate> states;
  if (initialized_) {
    if (auto s = track(frame, imu_since_previous)) states.push_back(*s);
    report_.optimization_ms = elapsed_ms();
    return states;
  }
  report_.state = "initializing";
  bootstrap(to_bootstrapper, imu_since_previous, states);
  report_.optimization_ms = elapsed_ms();
  return states;
}

void SlidingWindowEstimator::bootstrap(const FeatureFrame& frame,
                                       const std::vector<ImuSample>& imu_since_previous,
                                       std::vector<StateEstimate>& states) {
  auto init = bootstrapper_.addFrame(frame, imu_since_previous);
  status_ = bootstrapper_.status();
  status_detail_ = bootstrapper_.statusDetail();
  if (!init) return;
  // A late window was screened at its own time: the planes found moving since are taken out.
  const bool late = !init->frames_after.empty();
  if (late)
    for (auto& keyframe : init->keyframes) keyframe.features = screenedNow(keyframe.features);
  startWindow(*init);
  if (late) forgetUnseenPlanes();
  report_.state = "tracking";
  StateEstimate s;
  s.t = window_.back()->features.t;  // corrected if the time offset was
  std::copy(window_.back()->pose, window_.back()->pose + 7, s.pose);
  s.keyframe = true;
  states.push_back(s);
  if (!late) return;
  // The late initialization's frames since its window, this one last. After a reset among them,
  // the rest go to the bootstrapper as new frames would (its dead reckoning needs their IMU).
  for (const auto& [later, samples] : init->frames_after) {
    if (!initialized_) {
      bootstrap(later, samples, states);
      continue;
    }
    report_.finished_keyframe_work |= finishKeyframeWork();
    if (auto tracked = track(screenedNow(later), samples)) states.push_back(*tracked);
  }
}

std::optional<StateEstimate> SlidingWindowEstimator::track(
    const FeatureFrame& frame, const std::vector<ImuSample>& imu_since_previous) {
  const Frame& previous = *window_.back();
  auto f = std::make_unique<Frame>();
  f->id = next_frame_id_++;
  f->features = frame;
  f->imu = imu_since_previous;
  f->imu_from_previous =
      imu_link_.preintegrate(f->imu, previous.features.t, frame.t, previous.speed_bias);
  if (!f->imu_from_previous) {
    reset("no IMU between frames", imu_since_previous);
    return std::nullopt;
  }
  imu_link_.predict(previous.pose, previous.speed_bias, *f->imu_from_previous, f->pose,
                    f->speed_bias);
  double predicted[7];
  std::copy(f->pose, f->pose + 7, predicted);
  features_.addFrame(f->id, frame);
  window_.push_back(std::move(f));

  const bool keyframe = secondNewestIsKeyframe();
  planes_.choose(features_, homographyEligible());
  features_.triangulate(cameraLookup(), options_.min_triangulation_angle_deg * M_PI / 180,
                        kMinDepth, kMaxDepth);
  planes_.initialize(features_, cameraLookup(), camera(window_.back()->id).translation(),
                     map_.planesMap());
  // The planes go to the map after the oldest frame's marginalization.
  if (keyframe && window_.size() > options_.window_size + 1) {
    if (options_.homography_planes != HomographyPlanes::kNone) ++keyframes_since_covariances_;
    optimize(WindowSolve::kWindowAndPlaneCovariances);
  } else if (keyframe || !options_.motion_only_between_keyframes)
    optimize(WindowSolve::kWindow);
  else
    optimize(WindowSolve::kNewestFrames);
  rejectDepthOutliers();
  if (report_.features >= options_.min_features) last_seen_features_t_ = frame.t;
  const std::string why = failure(predicted);
  if (!why.empty()) {
    reset(why, imu_since_previous);  // the samples from the last good state (the previous frame) on
    return std::nullopt;
  }
  StateEstimate s;
  s.t = frame.t;
  std::copy(window_.back()->pose, window_.back()->pose + 7, s.pose);
  s.keyframe = keyframe;
  bootstrapper_.setGoodState(frame.t, window_.back()->pose, window_.back()->speed_bias);
  if (!keyframe)
    dropSecondNewest();
  else if (window_.size() > options_.window_size + 1 && !keyframe_work_deferred_)
    marginalizeOldest();
  report_.state = "tracking";
  return s;
}

}  // namespace rpvio
