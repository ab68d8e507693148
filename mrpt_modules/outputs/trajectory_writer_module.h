#pragma once
// Output module: the odometry's trajectory (trajectory.tum, every StateEstimate: body in world)
// and the batch refinement's keyframes (trajectory_refined.tum, from the MapSummary, when the
// refinement ran) and the poses the loop closure corrected (trajectory_loop.tum, from the
// LoopClosureSummary, when it ran), written into the pipeline's output folder at the end of the
// run.
#include "mrpt_modules/core/module.h"
#include "mrpt_modules/estimator/estimator_types.h"
#include "mrpt_modules/estimator/map_sink.h"
#include "mrpt_modules/loop/loop_closure_module.h"

namespace rpvio {

/// The TUM pose of a state estimate (body in world).
StampedPose stampedPose(const StateEstimate& state);
Trajectory toTrajectory(const std::vector<StateEstimate>& states);

class TrajectoryWriterModule : public Module {
  DEFINE_MRPT_OBJECT(TrajectoryWriterModule, rpvio)

 public:
  void initialize(const IniFile& config, const std::string& section,
                  PipelineContext& context) override;
  void finish() override;

 private:
  std::string output_dir_;
  Trajectory odometry_, refined_, loop_;
};

}  // namespace rpvio
