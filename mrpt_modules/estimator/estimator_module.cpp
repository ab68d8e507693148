#include "mrpt_modules/estimator/estimator_module.h"

#include <cmath>

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
  auto count = [&](const char* key, size_t fallback) {
    const double v = ini.numberOr(s, key, static_cast<double>(fallback));
    if (v < 0 || v != std::floor(v))
      throw InputError(ini.path(), "line " + std::to_string(ini.line(s, key)),
                       std::string(key) + " must be a non-negative integer");
    return static_cast<size_t>(v);
  };
  o.window_size = count("window_size", o.window_size);
  o.keyframe_parallax_px = ini.numberOr(s, "keyframe_parallax_px", o.keyframe_parallax_px);
  o.keyframe_min_tracks = count("keyframe_min_tracks", o.keyframe_min_tracks);
  o.max_keyframe_gap_s = ini.numberOr(s, "max_keyframe_gap_s", o.max_keyframe_gap_s);
  const std::string homography = ini.textOr(s, "homography_planes", "largest");
  if (homography == "none")
    o.homography_planes = HomographyPlanes::kNone;
  else if (homography == "largest")
    o.homography_planes = HomographyPlanes::kLargest;
  else if (homography == "all")
    o.homography_planes = HomographyPlanes::kAll;
  else
    throw InputError(ini.path(), "line " + std::to_string(ini.line(s, "homography_planes")),
                     "homography_planes must be none, largest or all, not '" + homography + "'");
  o.pixel_sigma = ini.numberOr(s, "pixel_sigma", o.pixel_sigma);
  o.cauchy_scale = ini.numberOr(s, "cauchy_scale", o.cauchy_scale);
  o.imu_noise_inflation = ini.numberOr(s, "imu_noise_inflation", o.imu_noise_inflation);
  o.max_iterations = static_cast<int>(count("max_iterations", o.max_iterations));
  o.max_solver_time_s = ini.numberOr(s, "max_solver_time_s", o.max_solver_time_s);
  o.min_triangulation_angle_deg =
      ini.numberOr(s, "min_triangulation_angle_deg", o.min_triangulation_angle_deg);
  o.max_accel_bias = ini.numberOr(s, "max_accel_bias", o.max_accel_bias);
  o.max_gyro_bias = ini.numberOr(s, "max_gyro_bias", o.max_gyro_bias);
  o.max_jump_m = ini.numberOr(s, "max_jump_m", o.max_jump_m);
  o.max_jump_deg = ini.numberOr(s, "max_jump_deg", o.max_jump_deg);
  o.min_features = count("min_features", o.min_features);
  o.max_blind_s = ini.numberOr(s, "max_blind_s", o.max_blind_s);
  o.virtual_focal = ini.numberOr(s, "virtual_focal", o.virtual_focal);
  auto method = [&](const char* key, const char* fallback) {
    const std::string name = ini.textOr(s, key, fallback);
    if (name == "homography") return InitializerMethod::kPlanarHomography;
    if (name == "essential") return InitializerMethod::kEssentialMatrix;
    throw InputError(ini.path(), "line " + std::to_string(ini.line(s, key)),
                     std::string(key) + " must be homography or essential, not '" + name + "'");
  };
  o.init.method = method("initializer", "homography");
  o.reinit_method = method("reinitializer", "essential");
  o.init_fallback = ini.flagOr(s, "init_fallback", o.init_fallback);
  o.init_fallback_after_s = ini.numberOr(s, "init_fallback_after_s", o.init_fallback_after_s);
  o.reinit_max_relative_scale_sigma =
      ini.numberOr(s, "reinit_max_scale_sigma", o.reinit_max_relative_scale_sigma);
  o.max_reconnect_s = ini.numberOr(s, "max_reconnect_s", o.max_reconnect_s);
  o.batch_refinement = ini.flagOr(s, "batch_refinement", o.batch_refinement);
  o.batch_refinement_max_keyframes = static_cast<size_t>(ini.numberOr(
      s, "batch_refinement_max_keyframes", static_cast<double>(o.batch_refinement_max_keyframes)));
  o.estimate_time_offset = ini.flagOr(s, "estimate_time_offset", o.estimate_time_offset);
  o.min_time_offset_s = ini.numberOr(s, "min_time_offset_s", o.min_time_offset_s);
  o.max_time_offset_s = ini.numberOr(s, "max_time_offset_s", o.max_time_offset_s);
  o.init.min_window_s = ini.numberOr(s, "init_window_s", o.init.min_window_s);
  o.init.min_parallax_px = ini.numberOr(s, "init_parallax_px", o.init.min_parallax_px);
  o.init.virtual_focal = o.virtual_focal;
  o.init.pixel_sigma = o.pixel_sigma;
  o.planes_map = PlanesMapOptions::load(ini, "PlanesMap");
  if (o.window_size < 3)
    throw InputError(ini.path(), "[" + s + "]", "window_size must be at least 3");
  estimator_ = std::make_unique<SlidingWindowEstimator>(context.calibration, o);
  bus_ = &context.bus;
  context.bus.subscribeSensor(labels::kImu, [this](const auto& m) { onImu(m); });
  context.bus.subscribe<FeatureFrame>([this](const FeatureFrame& f) { onFrame(f); });
  MRPT_LOG_INFO_STREAM("window " << o.window_size
                                 << ", homography factors on planes: " << homography);
}

void SlidingWindowEstimatorModule::finish() {
  while (!pending_.empty()) processOldestPending();
  estimator_->finishMap();
  if (!estimator_->refinementReport().empty()) MRPT_LOG_INFO_STREAM(estimator_->refinementReport());
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
  const auto state = estimator_->addFrame(frame, samples);
  // The estimator may have corrected the offset on this frame: the frame's time moved with it.
  previous_frame_t_ = frame.t + (estimator_->timeOffset() - offset);
  if (!estimator_->timeOffsetNote().empty() && !time_offset_reported_) {
    time_offset_reported_ = true;
    MRPT_LOG_INFO_STREAM("t=" << frame.t << " s: " << estimator_->timeOffsetNote());
  }
  timings_.push_back({frame.t, estimator_->lastReport()});
  if (estimator_->status() != last_status_) {
    last_status_ = estimator_->status();
    if (estimator_->lastReport().state == "reset")
      MRPT_LOG_WARN_STREAM("t=" << frame.t << " s: " << estimator_->statusDetail());
    else
      MRPT_LOG_INFO_STREAM("t=" << frame.t << " s: " << estimator_->statusDetail());
  }
  if (state) {
    if (initialized_at_ < 0) initialized_at_ = frame.t;
    bus_->publish(*state);
  }
}

}  // namespace rpvio
