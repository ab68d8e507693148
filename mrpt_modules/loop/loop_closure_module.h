#pragma once
// Pipeline module: loop closure over the keyframes leaving the estimator's window (KeyframeLeft).
// Each is described from its image (keyframe_appearance.h), looked up among the older ones
// (loop_detector.h) and added to a 4-DoF pose graph (four_dof_pose_graph.h), solved when a revisit
// is accepted; all on a thread of its own, off the frame path. Every pose the estimator publishes
// is also corrected by the graph's latest correction (trajectory_loop.tum). So that a run gives the
// same output every time, a keyframe's result is taken when the keyframe `loop_result_lag` after
// it leaves (waiting for it then if the thread is behind). At the end of the run it publishes
// what it found and the corrected trajectory (LoopClosureSummary). Listed after the estimator,
// before the outputs. Options: section [LoopClosureModule] (LoopClosureOptions).
#include <deque>
#include <exception>
#include <future>
#include <map>
#include <memory>
#include <vector>

#include "mrpt_modules/core/module.h"
#include "mrpt_modules/core/serial_worker.h"
#include "mrpt_modules/estimator/estimator_types.h"
#include "mrpt_modules/estimator/map_sink.h"
#include "mrpt_modules/loop/four_dof_pose_graph.h"
#include "mrpt_modules/loop/loop_detector.h"
#include "rawlog_io/rawlog_reader.h"

namespace rpvio {

struct LoopClosureOptions {
  LoopDetectorOptions detection;
  PoseGraphOptions graph;
  int loop_solve_every = 10;  // keyframes at least between two solves of the graph
  int loop_result_lag = 2;    // keyframes (above)

  template <class Visitor>
  void fields(Visitor& v) {
    detection.fields(v);
    graph.fields(v);
    RPVIO_OPTION(v, loop_solve_every);
    RPVIO_OPTION(v, loop_result_lag);
  }
};

/// Published by the loop closure module at the end of the run.
struct LoopClosureSummary {
  size_t keyframes = 0;           // described and stored
  std::vector<LoopEvent> events;  // in the order of the query keyframes
  Trajectory corrected;           // every published pose, corrected as it was published
};

class LoopClosureModule : public Module {
  DEFINE_MRPT_OBJECT(LoopClosureModule, rpvio)

 public:
  void initialize(const IniFile& config, const std::string& section,
                  PipelineContext& context) override;
  void finish() override;

 private:
  void onKeyframe(const KeyframeLeft& left);
  /// On the worker: one keyframe through detection and the graph; the graph's correction at it.
  Eigen::Isometry3d processKeyframe(double t, const ImageFileRef& image,
                                    const std::vector<AppearancePoint>& tracked,
                                    const Eigen::Isometry3d& body);
  void takeResult();

  const Bus* bus_ = nullptr;
  CameraIntrinsics camera_;
  LoopClosureOptions options_;
  std::map<double, ImageFileRef> images_;  // by image time, until their keyframe has left
  Eigen::Isometry3d correction_ = Eigen::Isometry3d::Identity();  // applied to published poses
  Trajectory corrected_;
  std::deque<std::future<Eigen::Isometry3d>> results_;
  // Used on worker_ only:
  std::unique_ptr<LoopDetector> detector_;
  std::unique_ptr<FourDofPoseGraph> graph_;
  std::vector<LoopEvent> events_;
  int keyframes_since_solve_ = 1 << 20;  // the first loop is solved at once
  bool loop_unsolved_ = false;
  std::exception_ptr error_;              // the first a task threw
  std::unique_ptr<SerialWorker> worker_;  // last: joined first
};

}  // namespace rpvio
