#include "mrpt_modules/estimator/estimator_module.h"

#include <mrpt/core/initializer.h>

#include "common/input_error.h"
#include "rawlog_io/rawlog_labels.h"
#include "rawlog_io/rawlog_reader.h"

IMPLEMENTS_MRPT_OBJECT(SlidingWindowEstimatorModule, rpvio::Module, rpvio)

// Registered with MRPT RTTI when the program loads, so a config can name it.
MRPT_INITIALIZER(register_SlidingWindowEstimatorModule) {
  mrpt::rtti::registerClass(CLASS_ID(rpvio::SlidingWindowEstimatorModule));
}

namespace rpvio {

void SlidingWindowEstimatorModule::initialize(const IniFile& ini, const std::string& s,
                                              PipelineContext& context) {
  const EstimatorOptions o = loadOptions<EstimatorOptions>(ini, s);
  bus_ = &context.bus;
  map_sink_ = std::make_unique<BusMapSink>(context.bus);
  context.bus.subscribe<MapReady>([this](const MapReady& m) { map_sink_->setMap(m.planes_map); });
  estimator_ = std::make_unique<SlidingWindowEstimator>(context.calibration, o, *map_sink_);
  context.bus.subscribeSensor(labels::kImu, [this](const auto& m) { onImu(m); });
  context.bus.subscribe<FeatureFrame>([this](const FeatureFrame& f) { onFrame(f); });
  setOptionsText("[" + s + "]\n" + describeOptions(o));
}

void SlidingWindowEstimatorModule::finish() {
  while (!pending_.empty()) processOldestPending();
  estimator_->finishMap();
  EstimatorSummary summary;
  summary.initialized_at = initialized_at_;
  summary.time_offset_s = estimator_->timeOffset();
  summary.time_offset_note = estimator_->timeOffsetNote();
  summary.resets = estimator_->resetLog();
  summary.status =
      estimator_->status() == "tracking" ? estimator_->status() : estimator_->statusDetail();
  summary.rejected_planes = estimator_->planeRejections();
  summary.planes_discovered = estimator_->planesDiscovered();
  summary.discoveries = estimator_->planeDiscoveries();
  bus_->publish(summary);
}

void SlidingWindowEstimatorModule::onImu(const ObservationMessage& m) {
  imu_.push_back(
      toImuSample(dynamic_cast<const mrpt::obs::CObservationIMU&>(*m.observation), *m.reader));
  processReadyFrames();
}

void SlidingWindowEstimatorModule::onFrame(const FeatureFrame& camera_frame) {
  pending_.push_back(camera_frame);
  processReadyFrames();
}

void SlidingWindowEstimatorModule::processReadyFrames() {
  // A frame waits until the IMU has reached its time on the IMU clock (a positive offset puts
  // the samples it needs after it in the rawlog).
  while (!pending_.empty() && !imu_.empty() &&
         imu_.back().t >= pending_.front().t + estimator_->timeOffset())
    processOldestPending();
}

void SlidingWindowEstimatorModule::processOldestPending() {
  FeatureFrame frame = std::move(pending_.front());
  pending_.pop_front();
  const double offset = estimator_->timeOffset();
  frame.t += offset;  // IMU clock
  // Samples since the previous frame, starting with the last one at or before it.
  std::vector<ImuSample> samples;
  while (imu_.size() > 1 && imu_[1].t <= previous_frame_t_) imu_.pop_front();
  for (const auto& s : imu_)
    if (s.t <= frame.t) samples.push_back(s);
  if (previous_frame_t_ < 0) samples.clear();
  const size_t rejected_before = estimator_->planeRejections().size();
  const auto states = estimator_->addFrame(frame, samples);
  for (size_t i = rejected_before; i < estimator_->planeRejections().size(); ++i) {
    const PlaneRejection& r = estimator_->planeRejections()[i];
    MRPT_LOG_WARN_FMT(
        "t=%s: plane %d moves against the camera's motion (median epipolar "
        "distance %.1f px): excluded",
        timeText(r.t).c_str(), r.plane_id, r.error_px);
  }
  // The estimator may have corrected the offset on this frame: the frame's time moved with it.
  previous_frame_t_ = frame.t + (estimator_->timeOffset() - offset);
  if (estimator_->timeOffsetNote() != reported_time_offset_note_) {
    reported_time_offset_note_ = estimator_->timeOffsetNote();
    MRPT_LOG_INFO_STREAM("t=" << timeText(frame.t) << ": " << estimator_->timeOffsetNote());
  }
  bus_->publish(EstimatorFrame{frame.t, estimator_->lastReport()});
  if (estimator_->status() != last_status_) {
    last_status_ = estimator_->status();
    if (estimator_->lastReport().state == "reset")
      MRPT_LOG_WARN_STREAM("t=" << timeText(frame.t) << ": " << estimator_->statusDetail());
    else
      MRPT_LOG_INFO_STREAM("t=" << timeText(frame.t) << ": " << estimator_->statusDetail());
  }
  if (!states.empty() && initialized_at_ < 0) initialized_at_ = frame.t;
  for (const StateEstimate& state : states) bus_->publish(state);
}

}  // namespace rpvio
