#pragma once
// The sliding-window estimator's start and restart: buffers the frames while not initialized, runs
// the initializers on them (the configured method; the essential-matrix fallback when its geometry
// fails; the re-initializer after a reset), estimates the camera-IMU time offset at the first
// initialization (and initializes again on the corrected frame times), and places a re-initialized
// window in the old world by IMU dead reckoning from the last good state.
#include <cmath>
#include <deque>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "mrpt_modules/core/feature_frame.h"
#include "mrpt_modules/estimator/estimator_options.h"
#include "mrpt_modules/imu/imu_link.h"
#include "mrpt_modules/initialization/initializer.h"

namespace rpvio {

/// An initialized window: keyframes evenly spaced over the initialization window, ending at its
/// newest frame, with the initializer's states.
struct InitializedWindow {
  struct Keyframe {
    FeatureFrame features;
    std::vector<ImuSample> imu;     // since the previous keyframe
    std::vector<double> skipped_t;  // the buffered frames between the previous keyframe and this
    double pose[7] = {0, 0, 0, 0, 0, 0, 1};
    double speed_bias[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  };
  std::vector<Keyframe> keyframes;
  std::map<int, Eigen::Vector3d> points;  // feature id: world point of the initializer's depth
  std::map<int, WorldPlane> planes;       // mask label: plane
  /// Frames after the newest keyframe as given to addFrame (not screened), each with its IMU
  /// samples since the previous one, to be tracked on the window at once: an initialization
  /// taken late (the window an undecided time offset waited on, when no longer window
  /// initialized); empty otherwise.
  std::vector<std::pair<FeatureFrame, std::vector<ImuSample>>> frames_after;
};

/// Moves a re-initialized window into the world of the last good state (both have z up).
struct WorldShift {
  Eigen::Quaterniond yaw;
  Eigen::Vector3d shift;
};

class Bootstrapper {
 public:
  Bootstrapper(const Calibration& calibration, const EstimatorOptions& options,
               const ImuLink& imu_link);

  /// A frame (IMU clock) with its samples since the previous one, while not initialized: the
  /// initialized window when an initializer succeeds on the buffered frames.
  std::optional<InitializedWindow> addFrame(const FeatureFrame& frame,
                                            const std::vector<ImuSample>& imu_since_previous);
  /// What the initializers see of each buffered frame, applied anew at every attempt (rpvio-auto:
  /// the plane labels discovered so far, which reach back to frames buffered before them).
  using FrameScreen = std::function<FeatureFrame(const FeatureFrame&)>;
  void setFrameScreen(FrameScreen screen) { screen_ = std::move(screen); }
  /// The state of a frame the estimator reported: where dead reckoning starts after a reset.
  void setGoodState(double t, const double* pose, const double* speed_bias);
  /// After a reset (`status` says why): the buffer starts anew; `imu_since_good` are the samples
  /// since the last good state.
  void restart(const std::vector<ImuSample>& imu_since_good, const std::string& status);
  /// Attempts that failed in their geometry, structure or alignment (each followed by
  /// init_retry_s without one).
  size_t expensiveFailures() const { return expensive_failures_; }
  /// Once per initialized window: the yaw and shift that put its first keyframe (time t, pose) on
  /// the IMU's dead reckoning from the last good state; none (a new world) when there is none or
  /// the IMU does not reach the keyframe. Forgets the last good state either way.
  std::optional<WorldShift> reconnect(double t, const double* pose);

  /// t_imu = t_frame + timeOffset(): the calibration's offset plus the estimated correction.
  double timeOffset() const { return time_offset_; }
  /// What the time-offset estimation found ("" before it ran).
  const std::string& timeOffsetNote() const { return time_offset_note_; }
  /// The time the buffered frames span (s): init_window_s, or more while a time offset waits.
  double bufferSpan() const {
    return buffer_.empty() ? 0 : buffer_.back().first.t - buffer_.front().first.t;
  }
  /// The last attempt's status ("tracking" on success) and its reason with figures.
  const std::string& status() const { return status_; }
  const std::string& statusDetail() const { return status_detail_; }

 private:
  /// The initializers on the buffered frames; the time offset the first time one succeeds.
  std::optional<InitializedWindow> tryInitialize();
  /// The window of a successful initialization on the buffered frames.
  InitializedWindow window(const std::vector<FeatureFrame>& frames,
                           const InitializationResult& init) const;
  /// The time offset estimated on the initialized window (once decided, the caller marks it
  /// estimated): td when significant (else 0), or undecided (the window is to grow to
  /// time_offset_window_s first).
  struct TimeOffsetDecision {
    double td = 0;
    bool undecided = false;
  };
  TimeOffsetDecision decideTimeOffset(const InitializationResult& init);
  /// At the end of an undecided offset's wait, before `frame` is buffered: the undecided window
  /// with the frames buffered since and `frame`, if the buffer still reaches back to it.
  std::optional<InitializedWindow> takeUndecidedWindow(
      InitializedWindow window, const FeatureFrame& frame,
      const std::vector<ImuSample>& imu_since_previous);
  /// The IMU samples of the buffer, in time order, once each.
  std::vector<ImuSample> bufferSamples() const;
  /// The body's orientation and velocity at time t by IMU dead reckoning from the last good state
  /// (after a reset), for the re-initialization's alignment; none before the first initialization.
  std::optional<KnownStart> knownStart(double t) const;
  /// The pose and speed_bias at time t by IMU dead reckoning from the last good state; false
  /// without one or without IMU samples.
  bool deadReckon(double t, double* pose, double* speed_bias) const;
  /// Moves the buffered frames (and the offset) by dt and deals their IMU samples out again.
  void moveBuffer(double dt);

  struct GoodState {
    double t = 0;
    double pose[7];
    double speed_bias[9];
  };

  Calibration calib_;
  EstimatorOptions options_;
  const ImuLink& imu_link_;
  Initializer initializer_;
  Initializer fallback_initializer_;  // when the configured method's geometry fails
  Initializer reinitializer_;         // after a reset
  std::deque<std::pair<FeatureFrame, std::vector<ImuSample>>> buffer_;
  FrameScreen screen_;  // none: the frames as given
  double time_offset_ = 0;
  bool time_offset_estimated_ = false;
  static constexpr int kTimeOffsetAttempts = 3;  // windows tried on corrected times
  int time_offset_attempts_ = 0;
  // While set, an undecided offset waits for a window of time_offset_window_s, until `until`;
  // `window` is the undecided window's initialization, taken when the wait ends.
  struct TimeOffsetWait {
    double until;
    InitializedWindow window;
  };
  std::optional<TimeOffsetWait> time_offset_wait_;
  std::string time_offset_note_;
  double next_attempt_t_ = -INFINITY;  // after an expensive failure (init_retry_s)
  size_t expensive_failures_ = 0;
  double first_fallback_cause_t_ = -1;     // the configured initializer failing in a way the
                                           // fallback takes (init_fallback_after_s)
  std::optional<GoodState> last_good_;     // newest state reported; kept through a reset
  std::vector<ImuSample> imu_since_good_;  // from last_good_ on, while re-initializing
  std::string status_ = "collecting frames";
  std::string status_detail_ = status_;
};

}  // namespace rpvio
