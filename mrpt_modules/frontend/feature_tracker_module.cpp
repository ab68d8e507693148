#include "mrpt_modules/frontend/feature_tracker_module.h"

#include <mrpt/core/initializer.h>

#include <algorithm>
#include <chrono>

#include "mrpt_modules/core/run_messages.h"
#include "mrpt_modules/imu/gyro_rotation.h"

#include "rawlog_io/rawlog_labels.h"
#include "rawlog_io/rawlog_reader.h"

IMPLEMENTS_MRPT_OBJECT(FeatureTrackerModule, rpvio::Module, rpvio)

// Registered with MRPT RTTI when the program loads, so a config can name it.
MRPT_INITIALIZER(register_FeatureTrackerModule) {
  mrpt::rtti::registerClass(CLASS_ID(rpvio::FeatureTrackerModule));
}

namespace rpvio {

void FeatureTrackerModule::initialize(const IniFile& config, const std::string& section,
                                      PipelineContext& context) {
  const TrackerOptions options = TrackerOptions::load(config, section);
  use_masks_ = options.use_masks;
  tracker_ = std::make_unique<FeatureTracker>(context.calibration.camera, options);
  bus_ = &context.bus;
  context.bus.subscribeSensor(labels::kCamera, [this](const auto& m) { onImage(m); });
  if (use_masks_)
    context.bus.subscribeSensor(labels::kPlaneMask, [this](const auto& m) { onMask(m); });
  if (options.predict_rotation) {
    R_BC_ = context.calibration.T_BC.linear();
    time_offset_ = context.calibration.time_offset;
    context.bus.subscribeSensor(labels::kImu, [this](const auto& m) { onImu(m); });
  }
  setOptionsText("[" + section + "]\n" + options.describe());
}

cv::Mat FeatureTrackerModule::timedLoad(const ObservationMessage& m) {
  const auto start = std::chrono::steady_clock::now();
  cv::Mat image =
      loadGrayImage(dynamic_cast<const mrpt::obs::CObservationImage&>(*m.observation), *m.reader);
  load_ms_ +=
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return image;
}

void FeatureTrackerModule::onImage(const ObservationMessage& m) {
  const double t = toSeconds(m.observation->timestamp);
  pending_images_[t] = timedLoad(m);
  process(t);
}

void FeatureTrackerModule::onMask(const ObservationMessage& m) {
  const double t = toSeconds(m.observation->timestamp);
  pending_masks_[t] = timedLoad(m);
  process(t);
}

void FeatureTrackerModule::onImu(const ObservationMessage& m) {
  gyro_.push_back(
      toImuSample(dynamic_cast<const mrpt::obs::CObservationIMU&>(*m.observation), *m.reader));
}

FeatureFrame FeatureTrackerModule::track(double t, const cv::Mat& image, const cv::Mat& mask) {
  // The camera's rotation since the previous image (gyro_rotation.h). Only samples before this
  // image's time take part (the last one's rate held up to it): which later ones have arrived
  // depends on how a rawlog orders equal times, the result must not.
  const double to = t + time_offset_;
  const std::vector<ImuSample> before(
      gyro_.begin(), std::lower_bound(gyro_.begin(), gyro_.end(), to,
                                      [](const ImuSample& s, double x) { return s.t < x; }));
  std::optional<Eigen::Matrix3d> R_cur_prev;
  if (previous_t_ && !before.empty() && t > *previous_t_)
    R_cur_prev = cameraRotationBetween(before, *previous_t_ + time_offset_, to, R_BC_);
  previous_t_ = t;
  // Samples before this image's time are no longer needed (keep the one at or before it).
  const auto first_needed = std::upper_bound(gyro_.begin(), gyro_.end(), to,
                                             [](double x, const ImuSample& s) { return x < s.t; });
  if (first_needed != gyro_.begin()) gyro_.erase(gyro_.begin(), first_needed - 1);
  return tracker_->track(t, image, mask, R_cur_prev ? &*R_cur_prev : nullptr);
}

void FeatureTrackerModule::process(double t) {
  const auto image = pending_images_.find(t);
  if (image == pending_images_.end()) return;
  cv::Mat mask;
  if (use_masks_) {
    const auto it = pending_masks_.find(t);
    if (it == pending_masks_.end()) return;  // wait for the mask of this image
    mask = it->second;
  }
  // Images without a mask by the time a later image is complete get none (said once).
  for (auto it = pending_images_.begin(); it != image;) {
    track(it->first, it->second, cv::Mat());
    it = pending_images_.erase(it);
  }
  const FeatureFrame frame = track(t, image->second, mask);
  pending_images_.erase(image);
  pending_masks_.erase(pending_masks_.begin(), pending_masks_.upper_bound(t));
  for (const auto& w : tracker_->takeWarnings())
    MRPT_LOG_WARN_STREAM("t=" << timeText(t) << ": " << w);
  bus_->publish(FrameDecoding{t, load_ms_});
  load_ms_ = 0;
  bus_->publish(frame);
}

void FeatureTrackerModule::finish() {
  if (!pending_images_.empty())
    MRPT_LOG_WARN_STREAM(pending_images_.size() << " image(s) never got their plane mask");
}

}  // namespace rpvio
