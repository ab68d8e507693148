// Fuzzes the trajectory readers (rawlog_io/trajectory_io.h): TUM, KITTI, EuRoC CSV and the format
// detection; returned poses must be finite, with unit quaternions and non-decreasing stamps.
#include <cstddef>
#include <cstdint>

#include "rawlog_io/trajectory_io.h"
#include "tests/fuzz/fuzz_util.h"

using namespace rpvio;

namespace {

void checkTrajectory(const Trajectory& traj) {
  for (size_t i = 0; i < traj.size(); ++i) {
    fuzz::require(std::isfinite(traj[i].t) && traj[i].p.allFinite(), "pose not finite");
    fuzz::require(fuzz::isUnit(traj[i].q), "pose quaternion not unit");
    fuzz::require(i == 0 || traj[i].t >= traj[i - 1].t, "timestamps going backwards");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const fuzz::InputFile file(data, size, "trajectory.txt");
  fuzz::readExpectingOnlyInputError([&] { checkTrajectory(readTrajectory(file.path())); });
  for (auto format : {TrajectoryFormat::Tum, TrajectoryFormat::Kitti, TrajectoryFormat::EurocCsv})
    fuzz::readExpectingOnlyInputError(
        [&] { checkTrajectory(readTrajectory(file.path(), format)); });
  return 0;
}
