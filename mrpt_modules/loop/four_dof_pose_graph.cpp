#include "mrpt_modules/loop/four_dof_pose_graph.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <stdexcept>

namespace rpvio {

Eigen::Vector3d yawPitchRoll(const Eigen::Matrix3d& R) {
  const double yaw = std::atan2(R(1, 0), R(0, 0));
  const double pitch = std::atan2(-R(2, 0), std::hypot(R(2, 1), R(2, 2)));
  const double roll = std::atan2(R(2, 1), R(2, 2));
  return {yaw, pitch, roll};
}

Eigen::Matrix3d fromYawPitchRoll(double yaw, double pitch, double roll) {
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

namespace {

/// The 4-DoF part of T: its yaw about the vertical and its translation.
Eigen::Isometry3d yawAndTranslation(const Eigen::Isometry3d& T) {
  Eigen::Isometry3d C = Eigen::Isometry3d::Identity();
  C.linear() =
      Eigen::AngleAxisd(yawPitchRoll(T.linear()).x(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  C.translation() = T.translation();
  return C;
}

}  // namespace

size_t FourDofPoseGraph::addMapKeyframe(const Eigen::Isometry3d& body) {
  if (nodes_.size() != map_nodes_) throw std::logic_error("FourDofPoseGraph: map keyframes first");
  const Eigen::Vector3d ypr = yawPitchRoll(body.linear());
  nodes_.push_back({body, ypr.y(), ypr.z(), {ypr.x()}, {}});
  Eigen::Map<Eigen::Vector3d>(nodes_.back().p.data()) = body.translation();
  return map_nodes_++;
}

size_t FourDofPoseGraph::addKeyframe(const Eigen::Isometry3d& odometry) {
  const Eigen::Vector3d ypr = yawPitchRoll(odometry.linear());
  Node node{odometry, ypr.y(), ypr.z(), {ypr.x()}, {}};
  // A new keyframe starts where the last correction puts it.
  const Eigen::Isometry3d start =
      nodes_.size() == map_nodes_ ? odometry : correction(size() - 1) * odometry;
  node.yaw[0] = yawPitchRoll(start.linear()).x();
  Eigen::Map<Eigen::Vector3d>(node.p.data()) = start.translation();
  nodes_.push_back(node);
  const size_t j = nodes_.size() - 1;
  for (size_t back = 1;
       back <= static_cast<size_t>(options_.loop_sequential_edges) && back <= j - map_nodes_;
       ++back)
    addEdge(j - back, j, nodes_[j - back].odometry, odometry, false);
  return j;
}

void FourDofPoseGraph::addLoop(size_t old, size_t query, const Eigen::Isometry3d& old_body) {
  if (old < map_nodes_ && !relocalized_) {
    // The run's world onto the map's: the old keyframe's pose in the map times its pose in the
    // run's world (the PnP's) inverted; yaw and translation only, both worlds are gravity-aligned.
    const Eigen::Isometry3d M = yawAndTranslation(corrected(old) * old_body.inverse());
    const double dyaw = yawPitchRoll(M.linear()).x();
    for (size_t k = map_nodes_; k < nodes_.size(); ++k) {
      Node& n = nodes_[k];
      const Eigen::Vector3d p = M * Eigen::Vector3d(n.p[0], n.p[1], n.p[2]);
      Eigen::Map<Eigen::Vector3d>(n.p.data()) = p;
      n.yaw[0] += dyaw;
    }
    relocalized_ = true;
  }
  addEdge(old, query, old_body, nodes_[query].odometry, true);
  ++loops_;
}

void FourDofPoseGraph::addEdge(size_t i, size_t j, const Eigen::Isometry3d& T_i,
                               const Eigen::Isometry3d& T_j, bool loop) {
  const Eigen::Vector3d ypr_i = yawPitchRoll(T_i.linear());
  const Eigen::Vector3d ypr_j = yawPitchRoll(T_j.linear());
  // p̂_ij in the frame R(ψ_i, θ_i, φ_i) of the residual, the odometry's pitch and roll of i.
  const Eigen::Matrix3d R_i = fromYawPitchRoll(ypr_i.x(), nodes_[i].pitch, nodes_[i].roll);
  edges_.push_back({i, j, R_i.transpose() * (T_j.translation() - T_i.translation()),
                    ypr_j.x() - ypr_i.x(), loop});
}

void FourDofPoseGraph::optimize() {
  if (nodes_.size() < 2 || loops_ == 0) return;
  ceres::Problem problem;
  for (const Edge& e : edges_) {
    auto* cost =
        new ceres::AutoDiffCostFunction<FourDofEdgeResidual, 4, 1, 3, 1, 3>(new FourDofEdgeResidual(
            e.p_ij, e.yaw_ij, nodes_[e.i].pitch, nodes_[e.i].roll, options_.loop_yaw_weight));
    problem.AddResidualBlock(
        cost, e.loop ? new ceres::CauchyLoss(options_.loop_edge_cauchy) : nullptr, nodes_[e.i].yaw,
        nodes_[e.i].p.data(), nodes_[e.j].yaw, nodes_[e.j].p.data());
  }
  // The gauge: the map's keyframes, or the run's first when it has not revisited the map.
  const size_t held = relocalized_ ? map_nodes_ : map_nodes_ + 1;
  for (size_t k = 0; k < std::min(held, nodes_.size()); ++k)
    if (problem.HasParameterBlock(nodes_[k].yaw)) {
      problem.SetParameterBlockConstant(nodes_[k].yaw);
      problem.SetParameterBlockConstant(nodes_[k].p.data());
    }
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  solver.max_num_iterations = 20;
  solver.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
}

Eigen::Isometry3d FourDofPoseGraph::corrected(size_t k) const {
  const Node& n = nodes_[k];
  if (k < map_nodes_) return n.odometry;  // held: exactly as loaded
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = fromYawPitchRoll(n.yaw[0], n.pitch, n.roll);
  T.translation() = Eigen::Vector3d(n.p[0], n.p[1], n.p[2]);
  return T;
}

Eigen::Isometry3d FourDofPoseGraph::correction(size_t k) const {
  // A yaw about the vertical and a translation (the odometry's roll and pitch are kept).
  const double dyaw = nodes_[k].yaw[0] - yawPitchRoll(nodes_[k].odometry.linear()).x();
  Eigen::Isometry3d C = Eigen::Isometry3d::Identity();
  C.linear() = Eigen::AngleAxisd(dyaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  C.translation() = corrected(k).translation() - C.linear() * nodes_[k].odometry.translation();
  return C;
}

void FourDofPoseGraph::clearSession() {
  nodes_.resize(map_nodes_);
  edges_.clear();  // the map's keyframes have none
  loops_ = 0;
  relocalized_ = false;
}

}  // namespace rpvio
