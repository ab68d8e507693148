#include "mrpt_modules/estimator/bootstrapper.h"

#include <cmath>
#include <cstdio>
#include <utility>

#include "mrpt_modules/factors/parameter_blocks.h"
#include "mrpt_modules/initialization/time_offset.h"

namespace rpvio {

Bootstrapper::Bootstrapper(const Calibration& calibration, const EstimatorOptions& options,
                           const ImuLink& imu_link)
    : calib_(calibration),
      options_(options),
      imu_link_(imu_link),
      initializer_(calibration, options.initializerOptions()),
      fallback_initializer_(calibration,
                            [&] {
                              InitializerOptions o = options.initializerOptions();
                              o.method = InitializerMethod::kEssentialMatrix;
                              return o;
                            }()),
      reinitializer_(calibration,
                     [&] {
                       InitializerOptions o = options.initializerOptions();
                       o.max_relative_scale_sigma = options.reinit_max_scale_sigma;
                       o.method = options.reinitializer;
                       return o;
                     }()),
      time_offset_(calibration.time_offset) {
  initializer_.setMinLoggingLevel(mrpt::system::LVL_WARN);  // the estimator reports the status
  reinitializer_.setMinLoggingLevel(mrpt::system::LVL_WARN);
  fallback_initializer_.setMinLoggingLevel(mrpt::system::LVL_WARN);
}

std::optional<InitializedWindow> Bootstrapper::addFrame(
    const FeatureFrame& frame, const std::vector<ImuSample>& imu_since_previous) {
  if (last_good_) {
    appendSamples(imu_since_good_, imu_since_previous);
    if (frame.t - last_good_->t > options_.max_reconnect_s) {
      last_good_.reset();  // too long: the next initialization starts a new world
      imu_since_good_.clear();
    }
  }
  if (time_offset_wait_ && frame.t > time_offset_wait_->until) {
    // No initialization on the longer window in time: the offset stays as it is, and the window
    // it was undecided on initializes now, with the frames since tracked on it.
    InitializedWindow undecided = std::move(time_offset_wait_->window);
    time_offset_wait_.reset();
    time_offset_estimated_ = true;
    next_attempt_t_ = -INFINITY;
    time_offset_note_ += ": no initialization on a longer window, not applied";
    if (auto window = takeUndecidedWindow(std::move(undecided), frame, imu_since_previous))
      return window;
  }
  if (frame.features.empty()) buffer_.clear();  // no structure can span a blank frame
  buffer_.emplace_back(frame, imu_since_previous);
  // The newest init_window_frames frames, or more when they span less than init_window_s (a
  // camera faster than 20 Hz); time_offset_window_s while a time offset waits for that window,
  // after which the window shrinks back.
  const bool waiting = time_offset_wait_.has_value();
  const double keep_s = waiting ? options_.time_offset_window_s : options_.init_window_s;
  while (buffer_.size() > 2 && (waiting || buffer_.size() > options_.init_window_frames) &&
         buffer_.back().first.t - buffer_[1].first.t >= keep_s - 1e-6)
    buffer_.pop_front();
  // Before the first initialization, an attempt that failed as far as the geometry or the
  // alignment (0.1–0.9 s of structure from motion and bundle adjustment) is not repeated before
  // the window has moved by init_retry_s. After a reset every frame is tried: the IMU alone
  // bridges the gap meanwhile, and a re-initialization may succeed on one frame only (the 4 s
  // blackout of tests/e2e/faults_test.cpp: at 13.5 s, which a 0.25 s spacing steps over).
  if (!last_good_ && frame.t < next_attempt_t_) return std::nullopt;
  auto window = tryInitialize();
  if (window) buffer_.clear();
  return window;
}

void Bootstrapper::setGoodState(double t, const double* pose, const double* speed_bias) {
  last_good_ = GoodState{t, {}, {}};
  std::copy(pose, pose + 7, last_good_->pose);
  std::copy(speed_bias, speed_bias + 9, last_good_->speed_bias);
}

void Bootstrapper::restart(const std::vector<ImuSample>& imu_since_good,
                           const std::string& status) {
  buffer_.clear();
  first_fallback_cause_t_ = -1;
  next_attempt_t_ = -INFINITY;
  time_offset_wait_.reset();
  imu_since_good_ = imu_since_good;
  status_ = status_detail_ = status;
}

std::optional<InitializedWindow> Bootstrapper::tryInitialize() {
  std::vector<FeatureFrame> frames;
  std::vector<std::shared_ptr<ImuPreintegration>> imu;
  // Preintegrations linearized at the last good biases after a reset, at zero before the first
  // initialization.
  const double zero[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  const double* biases = last_good_ ? last_good_->speed_bias : zero;
  for (size_t k = 0; k < buffer_.size(); ++k) {
    frames.push_back(screen_ ? screen_(buffer_[k].first) : buffer_[k].first);
    imu.push_back(k == 0 ? nullptr
                         : imu_link_.preintegrate(buffer_[k].second, buffer_[k - 1].first.t,
                                                  frames.back().t, biases, &calib_.imu));
    if (k > 0 && !imu.back()) return std::nullopt;  // a frame without IMU: wait for a clean window
  }
  InitializationResult init =
      last_good_ ? reinitializer_.tryInitialize(frames, imu, knownStart(frames[0].t))
                 : initializer_.tryInitialize(frames, imu);
  // The fallback also takes a full window on which the planar initializer found no plane with
  // the features and parallax for it: without masks a forward-moving camera groups few tracks
  // into planes early on (docs/notes/2026-12-05-real-street-images.md).
  const bool no_plane_pair = init.status == InitStatus::kTooFewPlaneFeatures ||
                             init.status == InitStatus::kTooLittleParallax;
  if (!last_good_ && (init.status == InitStatus::kGeometryFailed || no_plane_pair) &&
      options_.init_fallback && options_.initializer != InitializerMethod::kEssentialMatrix) {
    if (first_fallback_cause_t_ < 0) first_fallback_cause_t_ = frames.back().t;
    if (frames.back().t - first_fallback_cause_t_ >= options_.init_fallback_after_s)
      init = fallback_initializer_.tryInitialize(frames, imu);
  }
  status_ = init.ok() ? "tracking" : toString(init.status);
  status_detail_ = init.reason;
  if (init.status == InitStatus::kTooLittleImuExcitation ||
      init.status == InitStatus::kGeometryFailed || init.status == InitStatus::kAlignmentRejected) {
    next_attempt_t_ = frames.back().t + options_.init_retry_s;
    ++expensive_failures_;
  }
  if (!init.ok()) return std::nullopt;
  if (options_.estimate_time_offset && !time_offset_estimated_) {
    const TimeOffsetDecision decision = decideTimeOffset(init);
    if (decision.undecided) {
      // Not initialized yet: the window grows to time_offset_window_s, whose longer span of
      // changing angular rate decides (docs/notes/2026-11-28-time-offset-guard.md); if no
      // window initializes within time_offset_window_s more, the offset is not applied and this
      // window is taken then (takeUndecidedWindow).
      if (!time_offset_wait_)
        time_offset_wait_ =
            TimeOffsetWait{frames.back().t + options_.time_offset_window_s, window(frames, init)};
      next_attempt_t_ = buffer_.front().first.t + options_.time_offset_window_s - 1e-6;
      status_ = "time offset undecided";
      char detail[80];
      std::snprintf(detail, sizeof detail, "time offset undecided: waiting for a window of %.1f s",
                    options_.time_offset_window_s);
      status_detail_ = detail;
      return std::nullopt;
    }
    time_offset_estimated_ = true;
    time_offset_wait_.reset();
    // A significant camera-IMU offset: the same window again, on the corrected frame times; kept
    // only if it initializes there.
    if (decision.td != 0) {
      const auto original = buffer_;
      const double original_offset = time_offset_;
      moveBuffer(decision.td);
      if (auto corrected = tryInitialize()) {
        time_offset_note_ += ": frame times corrected";
        return corrected;
      }
      buffer_ = original;
      time_offset_ = original_offset;
      // The corrected window can fail for its own reasons (the hand-held profile's first window
      // loses its structure whatever the times): the offset is estimated again at the next
      // initialization, up to kTimeOffsetAttempts windows, before an uncorrected one is taken.
      if (++time_offset_attempts_ < kTimeOffsetAttempts) {
        time_offset_estimated_ = false;
        next_attempt_t_ = frames.back().t + options_.init_retry_s;
        status_ = "time offset unconfirmed";
        status_detail_ = time_offset_note_ + ": no initialization on the corrected times yet";
        return std::nullopt;
      }
      time_offset_note_ += ": not applied (no initialization on the corrected times)";
      status_ = "tracking";
      status_detail_ = init.reason;
    }
  }
  return window(frames, init);
}

InitializedWindow Bootstrapper::window(const std::vector<FeatureFrame>& frames,
                                       const InitializationResult& init) const {
  // Keyframes: evenly spaced over the initialization window, ending at its newest frame.
  const size_t n = frames.size();
  const size_t step =
      std::max<size_t>(1, (n - 1 + options_.window_size - 2) / (options_.window_size - 1));
  std::vector<size_t> chosen;
  for (long k = static_cast<long>(n) - 1; k >= 0; k -= static_cast<long>(step))
    chosen.insert(chosen.begin(), static_cast<size_t>(k));
  InitializedWindow w;
  for (size_t c = 0; c < chosen.size(); ++c) {
    InitializedWindow::Keyframe f;
    f.features = frames[chosen[c]];
    setPoseBlock(init.T_w_b[chosen[c]], f.pose);
    for (int i = 0; i < 3; ++i) {
      f.speed_bias[i] = init.v_w[chosen[c]][i];
      f.speed_bias[3 + i] = init.ba[i];
      f.speed_bias[6 + i] = init.bg[i];
    }
    if (c > 0)
      for (size_t k = chosen[c - 1] + 1; k <= chosen[c]; ++k) {
        appendSamples(f.imu, buffer_[k].second);
        if (k < chosen[c]) f.skipped_t.push_back(frames[k].t);
      }
    w.keyframes.push_back(std::move(f));
  }
  // The initializer's depths (camera of the feature's first frame in its window) as world points.
  for (const auto& [id, depth] : init.depths) {
    const FeatureFrame& first = frames[depth.frame];
    const auto seen = std::find_if(first.features.begin(), first.features.end(),
                                   [&](const TrackedFeature& f) { return f.id == id; });
    if (seen == first.features.end()) continue;
    w.points[id] = init.T_w_b[depth.frame] * calib_.T_BC *
                   (depth.depth * Eigen::Vector3d(seen->normalized.x(), seen->normalized.y(), 1));
  }
  w.planes = init.planes;
  return w;
}

bool Bootstrapper::deadReckon(double t, double* pose, double* speed_bias) const {
  if (!last_good_) return false;
  std::vector<ImuSample> samples;
  for (const ImuSample& sample : imu_since_good_)
    if (sample.t <= t) samples.push_back(sample);
  const auto pre =
      imu_link_.preintegrate(samples, last_good_->t, t, last_good_->speed_bias, &calib_.imu);
  if (!pre) return false;
  imu_link_.predict(last_good_->pose, last_good_->speed_bias, *pre, pose, speed_bias);
  return true;
}

std::optional<KnownStart> Bootstrapper::knownStart(double t) const {
  double pose[7], speed_bias[9];
  if (!last_good_ || t <= last_good_->t || t - last_good_->t > options_.reinit_known_velocity_s ||
      !deadReckon(t, pose, speed_bias))
    return std::nullopt;
  return KnownStart{poseRotation(pose).toRotationMatrix(), Eigen::Vector3d(speed_bias)};
}

std::optional<WorldShift> Bootstrapper::reconnect(double t, const double* pose) {
  double predicted_pose[7], predicted_speed_bias[9];  // at the first keyframe
  const bool reckoned = deadReckon(t, predicted_pose, predicted_speed_bias);
  last_good_.reset();
  imu_since_good_.clear();
  if (!reckoned) return std::nullopt;
  // Both worlds have z up: they differ by a yaw and a translation.
  const Eigen::Matrix3d M = poseRotation(predicted_pose).toRotationMatrix() *
                            poseRotation(pose).toRotationMatrix().transpose();
  WorldShift s;
  s.yaw =
      Eigen::Quaterniond(Eigen::AngleAxisd(std::atan2(M(1, 0), M(0, 0)), Eigen::Vector3d::UnitZ()));
  s.shift = posePosition(predicted_pose) - s.yaw * posePosition(pose);
  return s;
}

Bootstrapper::TimeOffsetDecision Bootstrapper::decideTimeOffset(const InitializationResult& init) {
  std::vector<double> t;
  std::vector<Eigen::Matrix3d> R;
  for (size_t k = 0; k < buffer_.size(); ++k) {
    t.push_back(buffer_[k].first.t);
    R.push_back(init.T_w_b[k].linear());
  }
  std::string why;
  const auto e =
      estimateTimeOffset(t, R, bufferSamples(), init.bg, options_.max_time_offset_s, &why);
  const std::string earlier = time_offset_note_.empty() ? "" : time_offset_note_ + "; then ";
  if (!e) {
    time_offset_note_ = earlier + "time offset not estimated: " + why;
    return {};
  }
  // Significant: not noise (3 sigma) and more than the margin times what the residual could fake
  // (systematic). Noise-significant but within that margin: undecided while the window is
  // shorter than time_offset_window_s.
  const bool noise_significant =
      std::abs(e->td) >= options_.min_time_offset_s && std::abs(e->td) > 3 * e->sigma;
  const bool beyond_systematic =
      std::abs(e->td) > options_.time_offset_systematic_margin * e->systematic;
  const double span = bufferSpan();
  TimeOffsetDecision decision;
  decision.undecided =
      noise_significant && !beyond_systematic && span < options_.time_offset_window_s - 1e-6;
  if (noise_significant && beyond_systematic) decision.td = e->td;
  char text[320];
  std::snprintf(text, sizeof text,
                "time offset %+.1f ms (sigma %.1f ms, systematic %.1f ms, %zu frames over %.1f s, "
                "fit %.4f deg, residual correlation %.2f)%s",
                1e3 * e->td, 1e3 * e->sigma, 1e3 * e->systematic, e->frames, span, e->rms_deg,
                e->residual_correlation,
                decision.undecided ? ": undecided, estimated again on a longer window"
                : decision.td != 0 ? ""
                                   : ": not applied");
  time_offset_note_ = earlier + text;
  return decision;
}

std::optional<InitializedWindow> Bootstrapper::takeUndecidedWindow(
    InitializedWindow window, const FeatureFrame& frame,
    const std::vector<ImuSample>& imu_since_previous) {
  const double newest = window.keyframes.back().features.t;
  // A blank frame since cleared the buffer: the frames after the window are not all there.
  if (buffer_.empty() || buffer_.front().first.t > newest) return std::nullopt;
  for (const auto& [buffered, imu] : buffer_)
    if (buffered.t > newest) window.frames_after.emplace_back(buffered, imu);
  window.frames_after.emplace_back(frame, imu_since_previous);
  buffer_.clear();
  status_ = "tracking";
  char detail[120];
  std::snprintf(detail, sizeof detail,
                "initialized on the window ending at t=%.2f s, %zu frames since tracked on it",
                newest, window.frames_after.size());
  status_detail_ = detail;
  return window;
}

std::vector<ImuSample> Bootstrapper::bufferSamples() const {
  std::vector<ImuSample> samples;
  for (const auto& [frame, imu] : buffer_) appendSamples(samples, imu);
  return samples;
}

void Bootstrapper::moveBuffer(double dt) {
  time_offset_ += dt;
  const std::vector<ImuSample> samples = bufferSamples();
  for (auto& [frame, imu] : buffer_) frame.t += dt;
  // Each frame's samples dealt out again: from the last one at or before the previous frame.
  for (size_t k = 0; k < buffer_.size(); ++k) {
    const double from = k == 0 ? -INFINITY : buffer_[k - 1].first.t;
    std::vector<ImuSample>& imu = buffer_[k].second;
    imu.clear();
    for (size_t j = 0; j < samples.size(); ++j)
      if (samples[j].t <= buffer_[k].first.t &&
          (samples[j].t > from || (j + 1 < samples.size() && samples[j + 1].t > from)))
        imu.push_back(samples[j]);
  }
}

}  // namespace rpvio
