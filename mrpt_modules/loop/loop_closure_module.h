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
// With a saved map (PipelineContext::maps.load, keyframe_map_file.h) its keyframes are candidates
// from the first keyframe on; the first accepted revisit of one relocalizes the run (its poses are
// published in the map's frame from then on). With maps.save the map's and the run's keyframes
// are saved at the end, in the map's frame (the run's only when it relocalized in a loaded map),
// with the plane map (DIR/planes.yaml) moved by the graph and merged with the loaded one.
#include <deque>
#include <exception>
#include <future>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "mrpt_modules/core/module.h"
#include "mrpt_modules/core/serial_worker.h"
#include "mrpt_modules/estimator/estimator_types.h"
#include "mrpt_modules/estimator/map_sink.h"
#include "mrpt_modules/loop/four_dof_pose_graph.h"
#include "mrpt_modules/loop/loop_detector.h"
#include "mrpt_modules/loop/planes_in_graph_frame.h"
#include "rawlog_io/rawlog_reader.h"

namespace rpvio {

struct LoopClosureOptions {
  LoopDetectorOptions detection;
  PoseGraphOptions graph;
  int loop_solve_every = 10;  // keyframes at least between two solves of the graph ...
  int loop_map_solves = 10;   // ... except at the first revisits of a loaded map's keyframes
  int loop_result_lag = 2;    // keyframes (above)

  template <class Visitor>
  void fields(Visitor& v) {
    detection.fields(v);
    graph.fields(v);
    RPVIO_OPTION(v, loop_solve_every);
    RPVIO_OPTION(v, loop_map_solves);
    RPVIO_OPTION(v, loop_result_lag);
  }
};

/// Published by the loop closure module at the end of the run.
struct LoopClosureSummary {
  size_t keyframes = 0;                 // described and stored
  size_t map_keyframes = 0;             // of them, loaded from a saved map
  std::optional<double> relocalized_t;  // the first pose published in the loaded map's frame
  std::vector<LoopEvent> events;        // in the order of the query keyframes
  Trajectory corrected;                 // every published pose, corrected as it was published
  // The plane map in the graph's frame after its last solve (planes_in_graph_frame.h), with the
  // loaded map's planes when the run relocalized in it; empty without a plane map.
  std::vector<Plane> planes;
};

class LoopClosureModule : public Module {
  DEFINE_MRPT_OBJECT(LoopClosureModule, rpvio)

 public:
  void initialize(const IniFile& config, const std::string& section,
                  PipelineContext& context) override;
  void finish() override;

 private:
  void onKeyframe(const KeyframeLeft& left);
  /// The persistent plane a track's plane label stands for now (0: none).
  int mapPlaneOf(int label) const;
  /// The graph's correction at a keyframe; `in_map`: it moves the run into the loaded map's frame.
  struct Correction {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    bool in_map = false;
  };
  /// On the worker: one keyframe through detection and the graph; the graph's correction at it.
  Correction processKeyframe(double t, const ImageFileRef& image,
                             const std::vector<AppearancePoint>& tracked,
                             const Eigen::Isometry3d& body);
  void takeResult();
  void loadMap(const std::string& dir, const Calibration& calibration);
  void saveMap(const std::string& dir, const std::vector<Plane>& planes) const;
  /// The run's keyframes' corrections after the graph's last solve.
  KeyframeCorrections runCorrections() const;

  const Bus* bus_ = nullptr;
  Calibration calibration_;
  MapFolders maps_;
  LoopClosureOptions options_;
  std::map<double, ImageFileRef> images_;  // by image time, until their keyframe has left
  Correction correction_;                  // applied to published poses
  std::optional<double> relocalized_t_;
  std::optional<std::vector<Plane>> run_planes_;  // the plane map's, at the end of the run
  std::vector<Plane> map_planes_;                 // the loaded map's
  const PlanesMap* planes_map_ = nullptr;         // the run's (MapReady)
  Trajectory corrected_;
  std::deque<std::future<Correction>> results_;
  // Used on worker_ only:
  std::unique_ptr<LoopDetector> detector_;
  std::unique_ptr<FourDofPoseGraph> graph_;
  std::vector<LoopEvent> events_;
  int keyframes_since_solve_ = 1 << 20;  // the first loop is solved at once
  bool loop_unsolved_ = false;
  int map_loops_ = 0;                     // accepted revisits of the map's keyframes
  std::exception_ptr error_;              // the first a task threw
  std::unique_ptr<SerialWorker> worker_;  // last: joined first
};

}  // namespace rpvio
