#include "mrpt_modules/estimator/batch_refinement.h"

#include <ceres/ceres.h>
#include <ceres/sphere_manifold.h>

#include <Eigen/Dense>
#include <algorithm>
#include <sstream>

#include "mrpt_modules/estimator/estimator_problem.h"
#include "mrpt_modules/factors/homography_factor.h"
#include "mrpt_modules/factors/imu_factor.h"
#include "mrpt_modules/factors/parameter_blocks.h"
#include "mrpt_modules/factors/pose_manifold.h"
#include "mrpt_modules/factors/reprojection_factor.h"

namespace rpvio {

std::vector<ArchivedObservation> keyframeObservations(
    uint64_t frame_id, const FeatureManager& features,
    const std::function<bool(const FeatureTrack&)>& in_use) {
  std::vector<ArchivedObservation> out;
  for (const auto& [id, track] : features.tracks()) {
    if (!in_use(track)) continue;
    for (const auto& o : track.observations)
      if (o.frame == frame_id) out.push_back({id, track.plane_id, o});
  }
  return out;
}

void KeyframeArchive::add(const ArchivedKeyframe& keyframe,
                          const std::vector<ArchivedObservation>& observations) {
  keyframes_.push_back(keyframe);
  for (const auto& o : observations) {
    FeatureTrack& archived = tracks_[o.id];
    archived.id = o.id;
    archived.plane_id = o.plane_id;
    archived.observations.push_back(o.observation);
  }
}

std::vector<StateEstimate> KeyframeArchive::trajectory() const {
  std::vector<StateEstimate> out;
  for (const auto& k : keyframes_) {
    StateEstimate e;
    e.t = k.t;
    std::copy(k.pose, k.pose + 7, e.pose);
    e.keyframe = true;
    out.push_back(e);
  }
  return out;
}

void KeyframeArchive::breakChain() {
  if (!keyframes_.empty()) keyframes_.back().to_next = nullptr;
}

BatchRefinement::BatchRefinement(KeyframeArchive& archive, const double* mount,
                                 const std::function<int(int)>& plane_of_label,
                                 std::map<int, PlaneEstimate>& planes,
                                 const BatchRefinementOptions& options)
    : archive_(archive), plane_of_label_(plane_of_label), planes_(planes), options_(options) {
  std::copy(mount, mount + 7, mount_);
}

bool BatchRefinement::solve() {
  auto& keyframes = archive_.keyframes_;
  if (keyframes.size() < 2) return false;
  const Eigen::Isometry3d T_BC = poseIsometry(mount_);
  std::map<uint64_t, double*> pose_of;
  std::map<uint64_t, Eigen::Isometry3d> cameras;
  for (auto& k : keyframes) {
    pose_of[k.id] = k.pose;
    cameras[k.id] = poseIsometry(k.pose) * T_BC;
  }
  const CameraPoseLookup lookup = [&](uint64_t id) { return cameras.at(id); };

  EstimatorProblem solve_problem(mount_, options_.cauchy_scale);
  ceres::Problem& problem = solve_problem.problem;
  const Eigen::Vector3d g(0, 0, -options_.gravity);
  // Gauge: the first keyframe of every IMU-chained segment keeps its position and yaw (the IMU
  // observes its tilt).
  bool segment_start = true;
  for (size_t i = 0; i < keyframes.size(); ++i) {
    auto& k = keyframes[i];
    problem.AddParameterBlock(k.pose, 7, &solve_problem.pose_manifold);
    problem.AddParameterBlock(k.speed_bias, 9);
    if (segment_start) {
      problem.SetManifold(k.pose, &solve_problem.gauge_manifold);
      ++segments_;
    }
    segment_start = !k.to_next || i + 1 == keyframes.size();
    if (!segment_start)
      problem.AddResidualBlock(new ImuFactor(k.to_next, g), nullptr, k.pose, k.speed_bias,
                               keyframes[i + 1].pose, keyframes[i + 1].speed_bias);
  }

  // Tracks with their depth; planes with enough tracks get homography factors.
  std::map<int, size_t> tracks_of_plane;
  std::vector<std::pair<FeatureTrack*, int>> usable;  // track, map plane (0: none)
  for (auto& [id, track] : archive_.tracks_) {
    if (track.observations.size() < 2) continue;
    if (widestRayAngle(track, lookup) < options_.min_parallax_rad) continue;
    const std::optional<double> depth = linearAnchorDepth(track, lookup);
    if (!depth || *depth <= 0) continue;
    track.inv_depth[0] = 1.0 / *depth;
    const int plane = track.plane_id > 0 ? plane_of_label_(track.plane_id) : 0;
    const bool known = plane > 0 && planes_.count(plane);
    usable.emplace_back(&track, known ? plane : 0);
    if (known) ++tracks_of_plane[plane];
  }
  size_t reprojections = 0, homographies = 0;
  for (auto& [track, plane] : usable) {
    const TrackObservation& anchor = track->observations.front();
    PlaneEstimate* p = plane > 0 && tracks_of_plane[plane] >= options_.min_plane_tracks
                           ? &planes_[plane]
                           : nullptr;
    for (size_t k = 1; k < track->observations.size(); ++k) {
      const TrackObservation& o = track->observations[k];
      problem.AddResidualBlock(
          ReprojectionResidual::create(anchor.normalized, o.normalized, options_.weight),
          &solve_problem.loss, pose_of[anchor.frame], pose_of[o.frame], mount_, track->inv_depth);
      ++reprojections;
      if (!p) continue;
      problem.AddResidualBlock(
          HomographyResidual::create(anchor.normalized, o.normalized, options_.weight),
          &solve_problem.loss, pose_of[anchor.frame], pose_of[o.frame], mount_, p->normal,
          p->distance);
      ++homographies;
    }
  }
  size_t planes = 0;
  for (auto& [id, p] : planes_)
    if (problem.HasParameterBlock(p.normal)) {
      problem.SetManifold(p.normal, &solve_problem.sphere);
      ++planes;
    }

  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::SPARSE_SCHUR;
  solver.max_num_iterations = options_.max_iterations;
  solver.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  std::ostringstream out;
  out << "batch refinement: " << keyframes.size() << " keyframes in " << segments_
      << " IMU-chained segment(s), " << usable.size() << " tracks, " << planes << " planes, "
      << reprojections << " reprojection and " << homographies << " homography factors; cost "
      << summary.initial_cost << " -> " << summary.final_cost << " in " << summary.iterations.size()
      << " iterations, " << summary.total_time_in_seconds << " s";
  report_ = out.str();
  seconds_ = summary.total_time_in_seconds;
  return summary.IsSolutionUsable();
}

}  // namespace rpvio
