#pragma once
// Pipeline module around FeatureTracker: consumes CAM0 (and PLANE_MASK when use_masks), pairs an
// image with the mask of the same timestamp (either arriving first) and publishes a FeatureFrame
// per image, after a FrameDecoding with the time its files took to decode. With
// predict_rotation it also consumes IMU and hands the tracker the camera's rotation since the
// previous image (the gyroscope's, integrated on the IMU clock: frame time + calibrated offset,
// gyroscope bias not corrected). With pipelined, images are decoded and tracked on a worker thread
// while the modules after this one work on earlier frames: a frame is published when the
// frames_in_flight-th image after it (or the run's end) arrives; the tracker still sees one image
// at a time, in order, so the outputs are those of a sequential run. Options: section
// [FeatureTrackerModule] (see TrackerOptions).
#include <Eigen/Geometry>
#include <deque>
#include <future>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "mrpt_modules/core/module.h"
#include "mrpt_modules/core/serial_worker.h"
#include "mrpt_modules/frontend/feature_tracker.h"
#include "mrpt_modules/imu/gravity_direction.h"
#include "rawlog_io/rawlog_reader.h"

namespace rpvio {

class FeatureTrackerModule : public Module {
  DEFINE_MRPT_OBJECT(FeatureTrackerModule, rpvio)

 public:
  void initialize(const IniFile& config, const std::string& section,
                  PipelineContext& context) override;
  void finish() override;

 private:
  /// Keeps where an image's (or a mask's) pixels are, by time, until its pair is complete.
  void onImageFile(std::map<double, ImageFileRef>& pending, const ObservationMessage& message);
  void onImu(const ObservationMessage& message);
  void process(double t);
  /// A tracked frame, what the tracker warned of on it, and the time its files took to decode.
  struct Tracked {
    FeatureFrame frame;
    std::vector<std::string> warnings;
    double load_ms = 0;
  };
  struct InFlight {
    double t = 0;
    bool on_bus = true;  // false: tracked, not published
    std::future<Tracked> tracked;
  };
  /// Decodes and tracks the image (on the worker when pipelined, publishing the oldest frame in
  /// flight once more than frames_in_flight are).
  void track(double t, const ImageFileRef& image, const std::optional<ImageFileRef>& mask,
             bool on_bus);
  /// The oldest frame in flight, once tracked, on the bus. A frame that failed (bad input) drops
  /// the frames after it, as a sequential run never gets to them, and throws.
  void publishOldest();
  void publishInFlight();
  void publish(double t, bool on_bus, const Tracked& tracked);
  std::optional<Eigen::Matrix3d> gyroRotationTo(double t);

  std::unique_ptr<FeatureTracker> tracker_;
  const Bus* bus_ = nullptr;
  bool use_masks_ = true;
  std::map<double, ImageFileRef> pending_images_, pending_masks_;
  double unpublished_load_ms_ = 0;  // decoding of tracked frames not published, for the next
  size_t frames_in_flight_ = 0;     // with worker_: frames tracked ahead of the bus
  std::deque<InFlight> in_flight_;
  std::unique_ptr<SerialWorker> worker_;  // after tracker_: its tasks use it until joined
  // Rotation prediction: the gyroscope since the previous image, the camera mount's rotation and
  // the camera-IMU offset of the calibration.
  std::vector<ImuSample> gyro_;
  std::optional<double> previous_t_;
  Eigen::Matrix3d R_BC_ = Eigen::Matrix3d::Identity();
  double time_offset_ = 0;
  // Gravity's direction for the ground tracks' horizon (with ground_features only), over the
  // samples up to each image's time; 3 s of a car's turn tilt it by a few degrees, not the
  // turn's 15.
  static constexpr double kGravityTimeConstantS = 3;
  std::optional<GravityDirection> gravity_;
  double gravity_until_ = -std::numeric_limits<double>::infinity();
};

}  // namespace rpvio
