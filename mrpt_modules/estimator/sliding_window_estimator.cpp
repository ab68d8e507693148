#include "mrpt_modules/estimator/sliding_window_estimator.h"

#include <Eigen/Dense>
#include <chrono>
#include <cmath>

#include "mrpt_modules/factors/parameter_blocks.h"

namespace rpvio {
namespace {

constexpr double kMinDepth = 0.1, kMaxDepth = 100;

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

Eigen::Isometry3d SlidingWindowEstimator::camera(uint64_t frame_id) const {
  for (const auto& f : window_)
    if (f->id == frame_id) return poseIsometry(f->pose) * calib_.T_BC;
  return Eigen::Isometry3d::Identity();  // not reached: tracks only reference window frames
}

CameraPoseLookup SlidingWindowEstimator::cameraLookup() const {
  return [this](uint64_t id) { return camera(id); };
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
  for (const StateEstimate& s : startedWindowStates(*init)) states.push_back(s);
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

std::vector<StateEstimate> SlidingWindowEstimator::startedWindowStates(
    const InitializedWindow& init) const {
  auto state = [](double t, const double* pose, bool keyframe) {
    StateEstimate s;
    s.t = t;
    std::copy(pose, pose + 7, s.pose);
    s.keyframe = keyframe;
    return s;
  };
  std::vector<StateEstimate> states;
  const size_t first = options_.publish_init_window ? 0 : window_.size() - 1;
  for (size_t k = first; k < window_.size(); ++k) {  // window_[k] started from init.keyframes[k]
    const Frame& keyframe = *window_[k];
    states.push_back(state(keyframe.features.t, keyframe.pose, true));
    if (k + 1 == window_.size()) break;
    for (const double t : init.keyframes[k + 1].skipped_t) {
      std::vector<ImuSample> samples;
      for (const ImuSample& sample : window_[k + 1]->imu)
        if (sample.t <= t) samples.push_back(sample);
      const auto pre = imu_link_.preintegrate(samples, keyframe.features.t, t, keyframe.speed_bias);
      if (!pre) continue;
      double pose[7], speed_bias[9];
      imu_link_.predict(keyframe.pose, keyframe.speed_bias, *pre, pose, speed_bias);
      states.push_back(state(t, pose, false));
    }
  }
  return states;
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
