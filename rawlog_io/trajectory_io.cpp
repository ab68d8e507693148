#include "rawlog_io/trajectory_io.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/atomic_file.h"
#include "common/input_error.h"
#include "common/text_table.h"

namespace rpvio {
namespace {

/// Calls `row` with the numbers of every data line (between min_count and max_count of them).
template <typename RowFn>
void forEachRow(const std::string& path, size_t min_count, size_t max_count, RowFn row) {
  forEachTextRow(path, [&](const std::vector<std::string>& fields, int line_no) {
    row(parseNumberRow(fields, min_count, max_count, path, line_no), line_no);
  });
}

void checkNotBackwards(const Trajectory& traj, double t, const std::string& path, int line_no) {
  // Equal stamps occur in real files (TUM RGB-D ground truth printed to 0.1 ms); only a step
  // backwards is an error.
  if (!traj.empty() && t < traj.back().t)
    throw InputError(path, "line " + std::to_string(line_no), "timestamp goes backwards");
}

}  // namespace

Trajectory readTum(const std::string& path) {
  Trajectory traj;
  forEachRow(path, 8, 8, [&](const std::vector<double>& v, int line_no) {
    checkNotBackwards(traj, v[0], path, line_no);
    StampedPose p;
    p.t = v[0];
    p.p = {v[1], v[2], v[3]};
    p.q = unitQuaternion(v[7], v[4], v[5], v[6], path, line_no);
    traj.push_back(p);
  });
  return traj;
}

Trajectory readKitti(const std::string& path) {
  Trajectory traj;
  forEachRow(path, 12, 12, [&](const std::vector<double>& v, int line_no) {
    Eigen::Matrix3d r;
    r << v[0], v[1], v[2], v[4], v[5], v[6], v[8], v[9], v[10];
    StampedPose p;
    p.t = static_cast<double>(traj.size());
    p.p = {v[3], v[7], v[11]};
    // Orthonormal with determinant +1 (a determinant near 1 alone lets shears through); written so
    // that NaN, from products of huge entries, fails too.
    if (!((r.transpose() * r - Eigen::Matrix3d::Identity()).norm() < 1e-3 && r.determinant() > 0))
      throw InputError(path, "line " + std::to_string(line_no), "rotation is not orthonormal");
    p.q = Eigen::Quaterniond(r).normalized();
    traj.push_back(p);
  });
  return traj;
}

Trajectory readEurocCsv(const std::string& path) {
  Trajectory traj;
  // #timestamp [ns], p_x, p_y, p_z, q_w, q_x, q_y, q_z [, v, bw, ba ...]
  forEachRow(path, 8, 64, [&](const std::vector<double>& v, int line_no) {
    StampedPose p;
    p.t = v[0] * 1e-9;
    checkNotBackwards(traj, p.t, path, line_no);
    p.p = {v[1], v[2], v[3]};
    p.q = unitQuaternion(v[4], v[5], v[6], v[7], path, line_no);
    traj.push_back(p);
  });
  return traj;
}

TrajectoryFormat detectTrajectoryFormat(const std::string& path) {
  int line_no = 0;
  const std::string line = firstTextRow(path, line_no);
  if (line.find(',') != std::string::npos) return TrajectoryFormat::EurocCsv;
  const size_t columns = splitTextFields(line).size();
  if (columns == 12) return TrajectoryFormat::Kitti;
  if (columns == 8) return TrajectoryFormat::Tum;
  throw InputError(path, "line " + std::to_string(line_no),
                   "unknown trajectory format (" + std::to_string(columns) +
                       " columns; TUM has 8, KITTI 12, EuRoC CSV is comma-separated)");
}

Trajectory readTrajectory(const std::string& path, TrajectoryFormat format) {
  switch (format) {
    case TrajectoryFormat::Kitti:
      return readKitti(path);
    case TrajectoryFormat::EurocCsv:
      return readEurocCsv(path);
    default:
      return readTum(path);
  }
}

Trajectory readTrajectory(const std::string& path) {
  return readTrajectory(path, detectTrajectoryFormat(path));
}

void writeTum(const std::string& path, const Trajectory& trajectory) {
  writeFileAtomically(path, [&](std::ostream& out) {
    char line[256];
    for (const StampedPose& p : trajectory) {
      const Eigen::Quaterniond q = p.q.normalized();
      std::snprintf(line, sizeof(line), "%.9f %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", p.t,
                    p.p.x(), p.p.y(), p.p.z(), q.x(), q.y(), q.z(), q.w());
      out << line;
    }
  });
}

}  // namespace rpvio
