// SlidingWindowEstimator's keyframe schedule (sliding_window_estimator.h): which frame leaves the
// window, the oldest keyframe's marginalization into the prior (or the second newest frame
// dropped), work deferred to the next frame, and what leaves to the map.
#include <map>
#include <memory>
#include <set>

#include "mrpt_modules/estimator/estimator_problem.h"
#include "mrpt_modules/estimator/sliding_window_estimator.h"
#include "mrpt_modules/factors/imu_factor.h"
#include "mrpt_modules/factors/reprojection_factor.h"
#include "mrpt_modules/factors/stacked_homography_factor.h"

namespace rpvio {

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
                                 anchor.normalized, o.normalized, trackWeight(track.plane_id))),
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
    marginalizer.addFactor(std::make_unique<StackedHomographyResiduals>(
                               std::move(features), trackWeight(plane_id), loss.get()),
                           nullptr,
                           {oldest.pose, pose_of[frame_j], mount_, plane.normal, plane.distance});
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
  k.image_t = frame.features.image_t;
  std::copy(frame.pose, frame.pose + 7, k.pose);
  std::copy(frame.speed_bias, frame.speed_bias + 9, k.speed_bias);
  if (ground_) k.ground_label = ground_->plane;
  // The window's factor, noise inflated (with the calibration's noise the refined trajectories of
  // the simulated static sequences were 1.0-2.3x worse).
  if (next) k.to_next = next->imu_from_previous;
  left.observations = keyframeObservations(frame.id, features_, inUse, cameraLookup());
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
  if (options_.camera_height_sigma > 0) {
    end.refinement.camera_height = calib_.camera_height;
    end.refinement.camera_height_sigma = options_.camera_height_sigma;
  }
  std::copy(mount_, mount_ + 7, end.mount);
  map_.windowFinished(end);
}

}  // namespace rpvio
