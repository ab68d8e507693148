#pragma once
// Pipeline module around FeatureTracker: consumes CAM0 (and PLANE_MASK when use_masks), pairs an
// image with the mask of the same timestamp (either arriving first) and publishes a FeatureFrame
// per image, after a FrameDecoding with the time its files took to decode. With
// predict_rotation it also consumes IMU and hands the tracker the camera's rotation since the
// previous image (the gyroscope's, integrated on the IMU clock: frame time + calibrated offset,
// gyroscope bias not corrected). With pipelined, an image is tracked on a worker thread while the
// modules after this one work on the previous frame, which is published when the next image (or
// the run's end) arrives; the tracker itself still sees one image at a time, in order. Options:
// section [FeatureTrackerModule] (see TrackerOptions).
#include <Eigen/Geometry>
#include <future>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "mrpt_modules/core/module.h"
#include "mrpt_modules/frontend/feature_tracker.h"

namespace rpvio {

class FeatureTrackerModule : public Module {
  DEFINE_MRPT_OBJECT(FeatureTrackerModule, rpvio)

 public:
  void initialize(const IniFile& config, const std::string& section,
                  PipelineContext& context) override;
  void finish() override;

 private:
  void onImage(const ObservationMessage& message);
  void onMask(const ObservationMessage& message);
  void onImu(const ObservationMessage& message);
  void process(double t);
  /// A frame being tracked, and what the tracker warned of on it.
  struct Tracked {
    FeatureFrame frame;
    std::vector<std::string> warnings;
  };
  struct InFlight {
    double t = 0;
    double load_ms = 0;
    bool on_bus = true;  // false: tracked, not published
    std::future<Tracked> tracked;
  };
  /// Tracks the image (on the worker when pipelined: then the frame before it is published).
  void track(double t, const cv::Mat& image, const cv::Mat& mask, bool on_bus);
  /// The frame in flight, once tracked, on the bus (with its warnings logged).
  void publishInFlight();
  void publish(InFlight done);
  std::optional<Eigen::Matrix3d> gyroRotationTo(double t);
  cv::Mat timedLoad(const ObservationMessage& message);

  std::unique_ptr<FeatureTracker> tracker_;
  const Bus* bus_ = nullptr;
  bool use_masks_ = true;
  std::map<double, cv::Mat> pending_images_, pending_masks_;
  double load_ms_ = 0;  // reading and decoding images and masks since the last frame
  bool pipelined_ = false;
  std::optional<InFlight> in_flight_;
  // Rotation prediction: the gyroscope since the previous image, the camera mount's rotation and
  // the camera-IMU offset of the calibration.
  std::vector<ImuSample> gyro_;
  std::optional<double> previous_t_;
  Eigen::Matrix3d R_BC_ = Eigen::Matrix3d::Identity();
  double time_offset_ = 0;
};

}  // namespace rpvio
