#pragma once
// Pipeline module: loop detection over the keyframes leaving the estimator's window
// (KeyframeLeft): each is described from its image (keyframe_appearance.h) and looked up among the
// older ones (loop_detector.h) on a thread of its own, off the frame path. At the end of the run it
// publishes what it found (LoopClosureSummary). Listed after the estimator, before the outputs.
// Options: section [LoopClosureModule] (LoopDetectorOptions).
#include <exception>
#include <future>
#include <map>
#include <memory>
#include <vector>

#include "mrpt_modules/core/module.h"
#include "mrpt_modules/core/serial_worker.h"
#include "mrpt_modules/estimator/map_sink.h"
#include "mrpt_modules/loop/loop_detector.h"
#include "rawlog_io/rawlog_reader.h"

namespace rpvio {

/// Published by the loop closure module at the end of the run.
struct LoopClosureSummary {
  size_t keyframes = 0;           // described and stored
  std::vector<LoopEvent> events;  // in the order of the query keyframes
};

class LoopClosureModule : public Module {
  DEFINE_MRPT_OBJECT(LoopClosureModule, rpvio)

 public:
  void initialize(const IniFile& config, const std::string& section,
                  PipelineContext& context) override;
  void finish() override;

 private:
  void onKeyframe(const KeyframeLeft& left);

  const Bus* bus_ = nullptr;
  CameraIntrinsics camera_;
  LoopDetectorOptions options_;
  std::map<double, ImageFileRef> images_;   // by image time, until their keyframe has left
  std::unique_ptr<LoopDetector> detector_;  // used on worker_ only
  std::vector<LoopEvent> events_;           // written on worker_ only
  std::exception_ptr error_;                // the first a task threw, on worker_ only
  std::future<void> last_task_;
  std::unique_ptr<SerialWorker> worker_;  // last: joined first
};

}  // namespace rpvio
