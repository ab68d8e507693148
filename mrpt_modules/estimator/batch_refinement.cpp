#include "mrpt_modules/estimator/batch_refinement.h"

#include <ceres/ceres.h>
#include <ceres/sphere_manifold.h>

#include <Eigen/Dense>
#include <algorithm>
#include <sstream>

#include "mrpt_modules/estimator/estimator_problem.h"
#include "mrpt_modules/factors/camera_height_factor.h"
#include "mrpt_modules/factors/homography_factor.h"
#include "mrpt_modules/factors/imu_factor.h"
#include "mrpt_modules/factors/parameter_blocks.h"
#include "mrpt_modules/factors/pose_manifold.h"
#include "mrpt_modules/factors/reprojection_factor.h"

namespace rpvio {

std::vector<ArchivedObservation> keyframeObservations(
    uint64_t frame_id, const FeatureManager& features,
    const std::function<bool(const FeatureTrack&)>& in_use, const CameraPoseLookup& cameras) {
  std::vector<ArchivedObservation> out;
  for (const auto& [id, track] : features.tracks()) {
    if (!in_use(track)) continue;
    for (const auto& o : track.observations) {
      if (o.frame != frame_id) continue;
      out.push_back({id, track.plane_id, o, std::nullopt});
      if (track.triangulated && track.inv_depth[0] > 0)
        out.back().world = features.worldPoint(track, cameras);
    }
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

namespace {

/// Every parameter block of the refinement in one array, in a fixed order: the mount, each
/// keyframe's pose and speed/bias, the planes, then the tracks' inverse depths. Ceres keeps the
/// blocks of a Schur ordering group in address order; in one array that order is this one, so the
/// solution does not depend on where the archive's blocks happen to live on the heap.
class ContiguousBlocks {
 public:
  explicit ContiguousBlocks(size_t size) : values_(size) {}
  /// The next `size` values, starting as a copy of `start`.
  double* take(const double* start, size_t size) {
    double* block = values_.data() + used_;
    std::copy(start, start + size, block);
    used_ += size;
    return block;
  }

 private:
  std::vector<double> values_;
  size_t used_ = 0;
};

}  // namespace

bool BatchRefinement::solve() {
  auto& keyframes = archive_.keyframes_;
  if (keyframes.size() < 2) return false;
  const Eigen::Isometry3d T_BC = poseIsometry(mount_);
  std::map<uint64_t, Eigen::Isometry3d> cameras;
  for (auto& k : keyframes) cameras[k.id] = poseIsometry(k.pose) * T_BC;
  const CameraPoseLookup lookup = [&](uint64_t id) { return cameras.at(id); };

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
  std::vector<int> solved_planes;
  for (const auto& [plane, count] : tracks_of_plane)
    if (count >= options_.min_plane_tracks) solved_planes.push_back(plane);

  ContiguousBlocks blocks(7 + 16 * keyframes.size() + 4 * solved_planes.size() + usable.size());
  double* mount = blocks.take(mount_, 7);
  std::map<uint64_t, double*> pose_of;
  std::vector<double*> speed_bias;
  for (auto& k : keyframes) {
    pose_of[k.id] = blocks.take(k.pose, 7);
    speed_bias.push_back(blocks.take(k.speed_bias, 9));
  }
  std::map<int, std::pair<double*, double*>> plane_blocks;  // normal, distance
  for (int plane : solved_planes)
    plane_blocks[plane] = {blocks.take(planes_[plane].normal, 3),
                           blocks.take(planes_[plane].distance, 1)};
  std::vector<double*> depths;
  for (auto& [track, plane] : usable) depths.push_back(blocks.take(track->inv_depth, 1));

  EstimatorProblem solve_problem(mount, options_.cauchy_scale);
  ceres::Problem& problem = solve_problem.problem;
  const Eigen::Vector3d g(0, 0, -options_.gravity);
  // Gauge: the first keyframe of every IMU-chained segment keeps its position and yaw (the IMU
  // observes its tilt).
  bool segment_start = true;
  for (size_t i = 0; i < keyframes.size(); ++i) {
    const auto& k = keyframes[i];
    double* pose = pose_of[k.id];
    problem.AddParameterBlock(pose, 7, &solve_problem.pose_manifold);
    problem.AddParameterBlock(speed_bias[i], 9);
    if (segment_start) {
      problem.SetManifold(pose, &solve_problem.gauge_manifold);
      ++segments_;
    }
    segment_start = !k.to_next || i + 1 == keyframes.size();
    if (!segment_start)
      problem.AddResidualBlock(new ImuFactor(k.to_next, g), nullptr, pose, speed_bias[i],
                               pose_of[keyframes[i + 1].id], speed_bias[i + 1]);
  }
  size_t reprojections = 0, homographies = 0;
  for (size_t j = 0; j < usable.size(); ++j) {
    const auto& [track, plane] = usable[j];
    const TrackObservation& anchor = track->observations.front();
    const auto p = plane_blocks.find(plane);
    for (size_t k = 1; k < track->observations.size(); ++k) {
      const TrackObservation& o = track->observations[k];
      problem.AddResidualBlock(
          ReprojectionResidual::create(anchor.normalized, o.normalized, options_.weight),
          &solve_problem.loss, pose_of[anchor.frame], pose_of[o.frame], mount, depths[j]);
      ++reprojections;
      if (p == plane_blocks.end()) continue;
      problem.AddResidualBlock(
          HomographyResidual::create(anchor.normalized, o.normalized, options_.weight),
          &solve_problem.loss, pose_of[anchor.frame], pose_of[o.frame], mount, p->second.first,
          p->second.second);
      ++homographies;
    }
  }
  size_t camera_heights = 0;
  for (const auto& k : keyframes) {
    if (options_.camera_height <= 0 || k.ground_label < 0) continue;
    const auto ground = plane_blocks.find(plane_of_label_(k.ground_label));
    if (ground == plane_blocks.end()) continue;
    const auto [normal, distance] = ground->second;
    const Eigen::Vector3d c = cameras.at(k.id).translation();
    const double side = Eigen::Vector3d(normal).dot(c) >= *distance ? 1 : -1;
    problem.AddResidualBlock(CameraHeightResidual::create(options_.camera_height, side,
                                                          1 / options_.camera_height_sigma),
                             nullptr, pose_of[k.id], mount, normal, distance);
    ++camera_heights;
  }
  for (const auto& [plane, block] : plane_blocks)
    problem.SetManifold(block.first, &solve_problem.sphere);

  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::SPARSE_SCHUR;
  solver.max_num_iterations = options_.max_iterations;
  solver.initial_trust_region_radius = options_.initial_trust_region_radius;
  // Eliminate the inverse depths only. Left to Ceres, the eliminated independent set also took
  // IMU speed/bias blocks, whose elimination fills the reduced system: 3x slower on an 80 s
  // sequence (docs/notes/2026-11-28-speed.md). Eliminating a depth couples every keyframe that
  // observes the track; one followed over hundreds of keyframes (a point in view for a whole
  // lap) makes the reduced system dense across that span. Such a depth stays in the reduced
  // system instead, one column that its fill-reducing ordering puts late.
  std::map<uint64_t, int> index_of;
  for (size_t i = 0; i < keyframes.size(); ++i) index_of[keyframes[i].id] = static_cast<int>(i);
  solver.linear_solver_ordering = std::make_shared<ceres::ParameterBlockOrdering>();
  for (size_t j = 0; j < usable.size(); ++j) {
    const auto& observations = usable[j].first->observations;
    const int span =
        index_of.at(observations.back().frame) - index_of.at(observations.front().frame);
    const bool eliminated = span <= options_.max_eliminated_track_span;
    solver.linear_solver_ordering->AddElementToGroup(depths[j], eliminated ? 0 : 1);
    if (!eliminated) ++long_tracks_;
  }
  std::vector<double*> all_blocks;
  problem.GetParameterBlocks(&all_blocks);
  for (double* block : all_blocks)
    if (!solver.linear_solver_ordering->IsMember(block))
      solver.linear_solver_ordering->AddElementToGroup(block, 1);
  solver.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  std::ostringstream out;
  out << "batch refinement: " << keyframes.size() << " keyframes in " << segments_
      << " IMU-chained segment(s), " << usable.size() << " tracks, " << plane_blocks.size()
      << " planes, " << reprojections << " reprojection and " << homographies
      << " homography factors, " << camera_heights << " camera heights (" << long_tracks_
      << " long tracks not eliminated); cost " << summary.initial_cost << " -> "
      << summary.final_cost << " in " << summary.iterations.size() << " iterations, "
      << summary.total_time_in_seconds << " s";
  report_ = out.str();
  seconds_ = summary.total_time_in_seconds;
  if (!summary.IsSolutionUsable()) return false;
  for (size_t i = 0; i < keyframes.size(); ++i) {
    const double* pose = pose_of[keyframes[i].id];
    std::copy(pose, pose + 7, keyframes[i].pose);
    std::copy(speed_bias[i], speed_bias[i] + 9, keyframes[i].speed_bias);
  }
  for (const auto& [plane, block] : plane_blocks) {
    std::copy(block.first, block.first + 3, planes_[plane].normal);
    planes_[plane].distance[0] = block.second[0];
  }
  for (size_t j = 0; j < usable.size(); ++j) usable[j].first->inv_depth[0] = depths[j][0];
  return true;
}

}  // namespace rpvio
