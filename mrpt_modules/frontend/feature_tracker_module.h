#pragma once
// Pipeline module around FeatureTracker: consumes CAM0 (and PLANE_MASK when use_masks), pairs an
// image with the mask of the same timestamp (either arriving first) and publishes a FeatureFrame
// per image, after a FrameDecoding with the time its files took to decode. With
// predict_rotation it also consumes IMU and hands the tracker the camera's rotation since the
// previous image (the gyroscope's, integrated on the IMU clock: frame time + calibrated offset,
// gyroscope bias not corrected). Options: section [FeatureTrackerModule] (see TrackerOptions).
#include <Eigen/Geometry>
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
  FeatureFrame track(double t, const cv::Mat& image, const cv::Mat& mask);
  cv::Mat timedLoad(const ObservationMessage& message);

  std::unique_ptr<FeatureTracker> tracker_;
  const Bus* bus_ = nullptr;
  bool use_masks_ = true;
  std::map<double, cv::Mat> pending_images_, pending_masks_;
  double load_ms_ = 0;  // reading and decoding images and masks since the last frame
  // Rotation prediction: the gyroscope since the previous image, the camera mount's rotation and
  // the camera-IMU offset of the calibration.
  std::vector<ImuSample> gyro_;
  std::optional<double> previous_t_;
  Eigen::Matrix3d R_BC_ = Eigen::Matrix3d::Identity();
  double time_offset_ = 0;
};

}  // namespace rpvio
