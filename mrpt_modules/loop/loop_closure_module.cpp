#include "mrpt_modules/loop/loop_closure_module.h"

#include <mrpt/core/initializer.h>

#include "rawlog_io/rawlog_labels.h"

IMPLEMENTS_MRPT_OBJECT(LoopClosureModule, rpvio::Module, rpvio)

// Registered with MRPT RTTI when the program loads, so a config can name it.
MRPT_INITIALIZER(register_LoopClosureModule) {
  mrpt::rtti::registerClass(CLASS_ID(rpvio::LoopClosureModule));
}

namespace rpvio {
namespace {

constexpr double kMaxImageGapS = 0.005;  // a keyframe's image: the nearest, this close

Eigen::Isometry3d bodyPose(const double pose[7]) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(pose[0], pose[1], pose[2]);
  T.linear() =
      Eigen::Quaterniond(pose[6], pose[3], pose[4], pose[5]).normalized().toRotationMatrix();
  return T;
}

}  // namespace

void LoopClosureModule::initialize(const IniFile& config, const std::string& section,
                                   PipelineContext& context) {
  options_ = loadOptions<LoopDetectorOptions>(config, section);
  camera_ = context.calibration.camera;
  detector_ = std::make_unique<LoopDetector>(options_, context.calibration.T_BC);
  worker_ = std::make_unique<SerialWorker>();
  bus_ = &context.bus;
  context.bus.subscribeSensor(labels::kCamera, [this](const ObservationMessage& m) {
    images_[toSeconds(m.observation->timestamp)] =
        locateImage(dynamic_cast<const mrpt::obs::CObservationImage&>(*m.observation), *m.reader);
  });
  context.bus.subscribe<KeyframeLeft>([this](const KeyframeLeft& k) { onKeyframe(k); });
  context.bus.subscribe<NewWorld>(
      [this](const NewWorld&) { last_task_ = worker_->submit([this] { detector_->clear(); }); });
  setOptionsText("[" + section + "]\n" + describeOptions(options_));
}

void LoopClosureModule::onKeyframe(const KeyframeLeft& left) {
  const double t = left.keyframe.t;
  auto nearest = images_.lower_bound(t - kMaxImageGapS);
  if (nearest == images_.end() || nearest->first > t + kMaxImageGapS) return;
  const ImageFileRef image = nearest->second;
  images_.erase(images_.begin(), std::next(nearest));  // keyframes leave in time order
  std::vector<AppearancePoint> tracked;
  for (const ArchivedObservation& o : left.observations)
    tracked.push_back({o.observation.normalized, o.world});
  const Eigen::Isometry3d body = bodyPose(left.keyframe.pose);
  last_task_ = worker_->submit([this, t, image, tracked = std::move(tracked), body] {
    if (error_) return;
    try {
      KeyframeAppearance appearance =
          describeKeyframe(decodeGrayImage(image), tracked, camera_, options_.loop_corners);
      if (auto event = detector_->add(t, body, std::move(appearance))) events_.push_back(*event);
    } catch (...) {
      error_ = std::current_exception();
    }
  });
}

void LoopClosureModule::finish() {
  if (last_task_.valid()) last_task_.get();  // the worker runs in order: everything is done
  if (error_) std::rethrow_exception(error_);
  LoopClosureSummary summary;
  summary.keyframes = detector_->keyframes();
  summary.events = events_;
  for (const LoopEvent& e : events_)
    MRPT_LOG_INFO_STREAM("loop " << timeText(e.t) << " -> " << timeText(e.t_old) << ": "
                                 << (e.check.accepted ? "accepted" : "rejected, " + e.check.why)
                                 << " (" << e.check.inliers << " inliers)");
  bus_->publish(summary);
}

}  // namespace rpvio
