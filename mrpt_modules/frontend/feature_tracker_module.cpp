#include "mrpt_modules/frontend/feature_tracker_module.h"

#include <mrpt/core/initializer.h>

#include <algorithm>
#include <chrono>
#include <utility>

#include "mrpt_modules/core/run_messages.h"
#include "mrpt_modules/estimator/estimator_types.h"
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
  if (options.pipelined) {
    frames_in_flight_ = size_t(options.frames_in_flight);
    worker_ = std::make_unique<SerialWorker>();
  }
  bus_ = &context.bus;
  context.bus.subscribeSensor(labels::kCamera,
                              [this](const auto& m) { onImageFile(pending_images_, m); });
  if (use_masks_)
    context.bus.subscribeSensor(labels::kPlaneMask,
                                [this](const auto& m) { onImageFile(pending_masks_, m); });
  if (options.predict_rotation) {
    R_BC_ = context.calibration.T_BC.linear();
    time_offset_ = context.calibration.time_offset;
    context.bus.subscribeSensor(labels::kImu, [this](const auto& m) { onImu(m); });
    // The estimator's attitude, once it has one, is the ground tracks' gravity (the newest pose
    // published; the rotation since its frame is left out: one frame of a turn).
    if (options.ground_features > 0) {
      gravity_.emplace(context.calibration.imu.gravity, kGravityTimeConstantS);
      context.bus.subscribe<StateEstimate>([this](const StateEstimate& s) {
        const Eigen::Quaterniond q_wb(s.pose[6], s.pose[3], s.pose[4], s.pose[5]);
        gravity_->set(q_wb.inverse() * -Eigen::Vector3d::UnitZ());
      });
    }
  }
  // The frames still in flight go out before the others hear of the run's end (this module
  // subscribes first when it is listed first, as the front-end is).
  context.bus.subscribe<RunEnd>([this](const RunEnd&) { publishInFlight(); });
  setOptionsText("[" + section + "]\n" + options.describe());
}

void FeatureTrackerModule::onImageFile(std::map<double, ImageFileRef>& pending,
                                       const ObservationMessage& m) {
  const double t = toSeconds(m.observation->timestamp);
  pending[t] =
      locateImage(dynamic_cast<const mrpt::obs::CObservationImage&>(*m.observation), *m.reader);
  process(t);
}

void FeatureTrackerModule::onImu(const ObservationMessage& m) {
  gyro_.push_back(
      toImuSample(dynamic_cast<const mrpt::obs::CObservationIMU&>(*m.observation), *m.reader));
}

std::optional<Eigen::Matrix3d> FeatureTrackerModule::gyroRotationTo(double t) {
  // The camera's rotation since the previous image (gyro_rotation.h). Only samples before this
  // image's time take part (the last one's rate held up to it): which later ones have arrived
  // depends on how a rawlog orders equal times, the result must not.
  const double to = t + time_offset_;
  const std::vector<ImuSample> before(
      gyro_.begin(), std::lower_bound(gyro_.begin(), gyro_.end(), to,
                                      [](const ImuSample& s, double x) { return s.t < x; }));
  if (gravity_)
    for (const ImuSample& s : before)
      if (s.t > gravity_until_) gravity_->add(s), gravity_until_ = s.t;
  std::optional<Eigen::Matrix3d> R_cur_prev;
  if (previous_t_ && !before.empty() && t > *previous_t_)
    R_cur_prev = cameraRotationBetween(before, *previous_t_ + time_offset_, to, R_BC_);
  previous_t_ = t;
  // Samples before this image's time are no longer needed (keep the one at or before it).
  const auto first_needed = std::upper_bound(gyro_.begin(), gyro_.end(), to,
                                             [](double x, const ImuSample& s) { return x < s.t; });
  if (first_needed != gyro_.begin()) gyro_.erase(gyro_.begin(), first_needed - 1);
  return R_cur_prev;
}

void FeatureTrackerModule::track(double t, const ImageFileRef& image,
                                 const std::optional<ImageFileRef>& mask, bool on_bus) {
  const auto R_cur_prev = gyroRotationTo(t);  // here: gyro_ grows on this thread
  std::optional<Eigen::Vector3d> down;
  if (gravity_ && gravity_->down()) down = R_BC_.transpose() * *gravity_->down();
  auto run = [this, t, image, mask, R_cur_prev, down] {
    const auto start = std::chrono::steady_clock::now();
    const cv::Mat pixels = decodeGrayImage(image);
    const cv::Mat mask_pixels = mask ? decodeGrayImage(*mask) : cv::Mat();
    Tracked r;
    r.load_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    r.frame = tracker_->track(t, pixels, mask_pixels, R_cur_prev ? &*R_cur_prev : nullptr,
                              down ? &*down : nullptr);
    r.warnings = tracker_->takeWarnings();
    return r;
  };
  if (!worker_) {
    publish(t, on_bus, run());
    return;
  }
  in_flight_.push_back({t, on_bus, worker_->submit(std::move(run))});
  while (in_flight_.size() > frames_in_flight_) publishOldest();
}

void FeatureTrackerModule::publishOldest() {
  InFlight oldest = std::move(in_flight_.front());
  in_flight_.pop_front();
  Tracked tracked;
  try {
    tracked = oldest.tracked.get();
  } catch (...) {
    in_flight_.clear();
    throw;
  }
  publish(oldest.t, oldest.on_bus, tracked);
}

void FeatureTrackerModule::publishInFlight() {
  while (!in_flight_.empty()) publishOldest();
}

void FeatureTrackerModule::publish(double t, bool on_bus, const Tracked& tracked) {
  for (const auto& w : tracked.warnings) MRPT_LOG_WARN_STREAM("t=" << timeText(t) << ": " << w);
  // Pipelined, the files are decoded on the worker: no decoding time on this thread.
  if (!worker_) unpublished_load_ms_ += tracked.load_ms;
  if (!on_bus) return;
  bus_->publish(FrameDecoding{t, std::exchange(unpublished_load_ms_, 0.0)});
  bus_->publish(tracked.frame);
}

void FeatureTrackerModule::process(double t) {
  const auto image = pending_images_.find(t);
  if (image == pending_images_.end()) return;
  std::optional<ImageFileRef> mask;
  if (use_masks_) {
    const auto it = pending_masks_.find(t);
    if (it == pending_masks_.end()) return;  // wait for the mask of this image
    mask = it->second;
  }
  // Images without a mask by the time a later image is complete get none (said once).
  for (auto it = pending_images_.begin(); it != image;) {
    track(it->first, it->second, std::nullopt, false);
    it = pending_images_.erase(it);
  }
  track(t, image->second, mask, true);
  pending_images_.erase(image);
  pending_masks_.erase(pending_masks_.begin(), pending_masks_.upper_bound(t));
}

void FeatureTrackerModule::finish() {
  if (!pending_images_.empty())
    MRPT_LOG_WARN_STREAM(pending_images_.size() << " image(s) never got their plane mask");
}

}  // namespace rpvio
