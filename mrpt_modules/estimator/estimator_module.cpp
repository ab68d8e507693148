#include "mrpt_modules/estimator/estimator_module.h"

#include <chrono>

#include "rawlog_io/input_error.h"
#include "rawlog_io/rawlog_labels.h"
#include "rawlog_io/rawlog_reader.h"

IMPLEMENTS_MRPT_OBJECT(SlidingWindowEstimatorModule, rpvio::Module, rpvio)

namespace rpvio {

void registerEstimatorModules() {
  mrpt::rtti::registerClass(CLASS_ID(SlidingWindowEstimatorModule));
}

void SlidingWindowEstimatorModule::initialize(const IniFile& ini, const std::string& s,
                                              PipelineContext& context) {
  EstimatorOptions o;
  o.window_size =
      static_cast<size_t>(ini.numberOr(s, "window_size", static_cast<double>(o.window_size)));
  o.keyframe_parallax_px = ini.numberOr(s, "keyframe_parallax_px", o.keyframe_parallax_px);
  o.max_keyframe_gap_s = ini.numberOr(s, "max_keyframe_gap_s", o.max_keyframe_gap_s);
  o.all_planes = ini.flagOr(s, "all_planes", o.all_planes);
  o.pixel_sigma = ini.numberOr(s, "pixel_sigma", o.pixel_sigma);
  o.cauchy_scale = ini.numberOr(s, "cauchy_scale", o.cauchy_scale);
  o.max_iterations = static_cast<int>(ini.numberOr(s, "max_iterations", o.max_iterations));
  o.init.min_window_s = ini.numberOr(s, "init_window_s", o.init.min_window_s);
  o.init.min_parallax_px = ini.numberOr(s, "init_parallax_px", o.init.min_parallax_px);
  if (o.window_size < 3)
    throw InputError(ini.path(), "[" + s + "]", "window_size must be at least 3");
  estimator_ = std::make_unique<SlidingWindowEstimator>(context.calibration, o);
  time_offset_ = context.calibration.time_offset;
  bus_ = &context.bus;
  context.bus.subscribeSensor(labels::kImu, [this](const auto& m) { onImu(m); });
  context.bus.subscribe<FeatureFrame>([this](const FeatureFrame& f) { onFrame(f); });
  MRPT_LOG_INFO_STREAM("window " << o.window_size << ", planes "
                                 << (o.all_planes ? "all" : "largest only"));
}

void SlidingWindowEstimatorModule::onImu(const ObservationMessage& m) {
  imu_.push_back(
      toImuSample(dynamic_cast<const mrpt::obs::CObservationIMU&>(*m.observation), *m.reader));
}

void SlidingWindowEstimatorModule::onFrame(const FeatureFrame& camera_frame) {
  FeatureFrame frame = camera_frame;
  frame.t += time_offset_;  // IMU clock
  // Samples since the previous frame, starting with the last one at or before it.
  std::vector<ImuSample> samples;
  while (imu_.size() > 1 && imu_[1].t <= previous_frame_t_) imu_.pop_front();
  for (const auto& s : imu_)
    if (s.t <= frame.t) samples.push_back(s);
  if (previous_frame_t_ < 0) samples.clear();
  previous_frame_t_ = frame.t;

  const auto start = std::chrono::steady_clock::now();
  const auto state = estimator_->addFrame(frame, samples);
  FrameTiming timing;
  timing.t = frame.t;
  timing.estimator_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  timing.features = frame.features.size();
  timing.tracking = state.has_value();
  timings_.push_back(timing);
  if (estimator_->status() != last_status_) {
    last_status_ = estimator_->status();
    MRPT_LOG_INFO_STREAM("t=" << frame.t << " s: " << last_status_);
  }
  if (state) {
    if (initialized_at_ < 0) initialized_at_ = frame.t;
    bus_->publish(*state);
  }
}

}  // namespace rpvio
