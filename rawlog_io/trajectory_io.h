#pragma once
// Trajectory files: TUM (`t tx ty tz qx qy qz qw`) read/write, KITTI (3x4 row-major, no stamps)
// read, EuRoC ground-truth CSV (`#timestamp [ns], p_RS_R_x..z, q_RS_w..z, ...`) read.
// Readers throw InputError naming the file and the line on malformed content.
#include <string>

#include "common/sensor_types.h"

namespace rpvio {

enum class TrajectoryFormat { Tum, Kitti, EurocCsv };

Trajectory readTum(const std::string& path);
Trajectory readKitti(const std::string& path);
Trajectory readEurocCsv(const std::string& path);
/// Recognizes the format from the content (comma-separated → EuRoC, 12 numbers → KITTI, 8 → TUM).
TrajectoryFormat detectTrajectoryFormat(const std::string& path);
Trajectory readTrajectory(const std::string& path, TrajectoryFormat format);
Trajectory readTrajectory(const std::string& path);  // detected format
/// Writes to a temporary name and renames it when complete; full double precision.
void writeTum(const std::string& path, const Trajectory& trajectory);

}  // namespace rpvio
