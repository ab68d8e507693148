#include "mrpt_modules/outputs/trajectory_writer_module.h"

#include <mrpt/core/initializer.h>

#include <filesystem>

#include "rawlog_io/trajectory_io.h"

IMPLEMENTS_MRPT_OBJECT(TrajectoryWriterModule, rpvio::Module, rpvio)

// Registered with MRPT RTTI when the program loads, so a config can name it.
MRPT_INITIALIZER(register_TrajectoryWriterModule) {
  mrpt::rtti::registerClass(CLASS_ID(rpvio::TrajectoryWriterModule));
}

namespace rpvio {

StampedPose stampedPose(const StateEstimate& s) {
  StampedPose p;
  p.t = s.t;
  p.p = Eigen::Vector3d(s.pose[0], s.pose[1], s.pose[2]);
  p.q = Eigen::Quaterniond(s.pose[6], s.pose[3], s.pose[4], s.pose[5]);
  return p;
}

Trajectory toTrajectory(const std::vector<StateEstimate>& states) {
  Trajectory trajectory;
  for (const auto& s : states) trajectory.push_back(stampedPose(s));
  return trajectory;
}

void TrajectoryWriterModule::initialize(const IniFile&, const std::string& section,
                                        PipelineContext& context) {
  output_dir_ = context.output_dir;
  context.bus.subscribe<StateEstimate>(
      [this](const StateEstimate& s) { odometry_.push_back(stampedPose(s)); });
  context.bus.subscribe<MapSummary>(
      [this](const MapSummary& s) { refined_ = toTrajectory(s.refined_trajectory); });
  context.bus.subscribe<LoopClosureSummary>(
      [this](const LoopClosureSummary& s) { loop_ = s.corrected; });
  setOptionsText("[" + section + "]\n");
}

void TrajectoryWriterModule::finish() {
  if (output_dir_.empty()) return;
  const std::filesystem::path dir(output_dir_);
  writeTum((dir / "trajectory.tum").string(), odometry_);
  if (!refined_.empty()) writeTum((dir / "trajectory_refined.tum").string(), refined_);
  if (!loop_.empty()) writeTum((dir / "trajectory_loop.tum").string(), loop_);
}

}  // namespace rpvio
