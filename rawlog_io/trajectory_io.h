#pragma once
// Trajectory files: TUM (`t tx ty tz qx qy qz qw`) read/write, KITTI (3x4 row-major, no stamps)
// read, EuRoC ground-truth CSV (`#timestamp [ns], p_RS_R_x..z, q_RS_w..z, ...`) read.
// Readers throw InputError naming the file and the line on malformed content.
#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace rpvio {

struct StampedPose {
  double t = 0;  // seconds; KITTI poses get their index as stamp
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
};
using Trajectory = std::vector<StampedPose>;

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
