#include "mrpt_modules/loop/loop_closure_module.h"

#include <mrpt/core/initializer.h>

#include "mrpt_modules/factors/parameter_blocks.h"
#include "rawlog_io/rawlog_labels.h"

IMPLEMENTS_MRPT_OBJECT(LoopClosureModule, rpvio::Module, rpvio)

// Registered with MRPT RTTI when the program loads, so a config can name it.
MRPT_INITIALIZER(register_LoopClosureModule) {
  mrpt::rtti::registerClass(CLASS_ID(rpvio::LoopClosureModule));
}

namespace rpvio {

void LoopClosureModule::initialize(const IniFile& config, const std::string& section,
                                   PipelineContext& context) {
  options_ = loadOptions<LoopClosureOptions>(config, section);
  camera_ = context.calibration.camera;
  detector_ = std::make_unique<LoopDetector>(options_.detection, context.calibration.T_BC);
  graph_ = std::make_unique<FourDofPoseGraph>(options_.graph);
  worker_ = std::make_unique<SerialWorker>();
  bus_ = &context.bus;
  context.bus.subscribeSensor(labels::kCamera, [this](const ObservationMessage& m) {
    images_[toSeconds(m.observation->timestamp)] =
        locateImage(dynamic_cast<const mrpt::obs::CObservationImage&>(*m.observation), *m.reader);
  });
  context.bus.subscribe<KeyframeLeft>([this](const KeyframeLeft& k) { onKeyframe(k); });
  context.bus.subscribe<StateEstimate>([this](const StateEstimate& s) {
    // Composed as quaternions: without a correction, exactly the odometry's pose.
    const Eigen::Quaterniond q_C(correction_.linear());
    corrected_.push_back({s.t, correction_ * posePosition(s.pose), q_C * poseRotation(s.pose)});
  });
  // Another world: the keyframes so far cannot be revisited in it.
  context.bus.subscribe<NewWorld>([this](const NewWorld&) {
    while (!results_.empty()) takeResult();
    worker_
        ->submit([this] {
          detector_->clear();
          graph_->clear();
          loop_unsolved_ = false;
          keyframes_since_solve_ = 1 << 20;
        })
        .get();
    correction_ = Eigen::Isometry3d::Identity();
  });
  setOptionsText("[" + section + "]\n" + describeOptions(options_));
}

void LoopClosureModule::onKeyframe(const KeyframeLeft& left) {
  const double t = left.keyframe.t;
  const auto found = images_.find(left.keyframe.image_t);
  if (found == images_.end()) return;
  const ImageFileRef image = found->second;
  images_.erase(images_.begin(), std::next(found));  // keyframes leave in time order
  std::vector<AppearancePoint> tracked;
  for (const ArchivedObservation& o : left.observations)
    tracked.push_back({o.observation.normalized, o.world});
  const Eigen::Isometry3d body = poseIsometry(left.keyframe.pose);
  results_.push_back(worker_->submit([this, t, image, tracked = std::move(tracked), body] {
    return processKeyframe(t, image, tracked, body);
  }));
  while (results_.size() > static_cast<size_t>(std::max(options_.loop_result_lag, 0))) takeResult();
}

Eigen::Isometry3d LoopClosureModule::processKeyframe(double t, const ImageFileRef& image,
                                                     const std::vector<AppearancePoint>& tracked,
                                                     const Eigen::Isometry3d& body) {
  if (error_) return Eigen::Isometry3d::Identity();
  try {
    KeyframeAppearance appearance =
        describeKeyframe(decodeGrayImage(image), tracked, camera_, options_.detection.loop_corners);
    const auto event = detector_->add(t, body, std::move(appearance));
    const size_t k = graph_->addKeyframe(body);
    if (event) {
      events_.push_back(*event);
      if (event->check.accepted) {
        graph_->addLoop(event->old_index, k, event->check.old_body);
        loop_unsolved_ = true;
      }
    }
    ++keyframes_since_solve_;
    if (loop_unsolved_ && keyframes_since_solve_ >= options_.loop_solve_every) {
      graph_->optimize();
      loop_unsolved_ = false;
      keyframes_since_solve_ = 0;
    }
    return graph_->correction(k);
  } catch (...) {
    error_ = std::current_exception();
    return Eigen::Isometry3d::Identity();
  }
}

void LoopClosureModule::takeResult() {
  correction_ = results_.front().get();
  results_.pop_front();
}

void LoopClosureModule::finish() {
  while (!results_.empty()) takeResult();
  if (error_) std::rethrow_exception(error_);
  LoopClosureSummary summary;
  summary.keyframes = detector_->keyframes();
  summary.events = events_;
  summary.corrected = corrected_;
  size_t accepted = 0;
  for (const LoopEvent& e : events_) accepted += e.check.accepted;
  MRPT_LOG_INFO_STREAM("loop closure: " << summary.keyframes << " keyframes, " << events_.size()
                                        << " revisits found by appearance, " << accepted
                                        << " accepted");
  bus_->publish(summary);
}

}  // namespace rpvio
