#pragma once
// After a run, one bundle adjustment over every keyframe the window let go (a batch smoother, as
// ORB-SLAM's final global BA): IMU factors chain consecutive keyframes, every track gives
// reprojection factors over its whole life, and a plane seen on several visits is one parameter
// block with the homography factors of all of them, so the laps close through the planes. The
// causal odometry stays the run's trajectory; the refinement gives the planes map its final
// (n, d) and a trajectory of its own.
#include <Eigen/Geometry>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "mrpt_modules/estimator/estimator_types.h"
#include "mrpt_modules/estimator/feature_manager.h"
#include "mrpt_modules/imu/imu_preintegration.h"

namespace rpvio {

struct ArchivedKeyframe {
  uint64_t id = 0;
  double t = 0;                            // IMU clock
  double image_t = 0;                      // its image's timestamp (FeatureFrame::image_t)
  double pose[7] = {0, 0, 0, 0, 0, 0, 1};  // body in world [p, q]
  double speed_bias[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  std::shared_ptr<const ImuPreintegration> to_next;  // null: no IMU factor to the next keyframe
  // The label of the window's ground plane when the window held this keyframe's camera at
  // calib.ini's camera_height over it (camera_height_factor.h); -1: none.
  int ground_label = -1;
};

/// A track's observation in a keyframe.
struct ArchivedObservation {
  int id = -1;  // feature id
  int plane_id = 0;
  TrackObservation observation;
  std::optional<Eigen::Vector3d> world;  // the track's point in the world, when triangulated
};

/// The observations keyframe `frame_id` holds of the tracks `in_use`, with their points as the
/// window's `cameras` place them.
std::vector<ArchivedObservation> keyframeObservations(
    uint64_t frame_id, const FeatureManager& features,
    const std::function<bool(const FeatureTrack&)>& in_use, const CameraPoseLookup& cameras);

/// Keyframes as they leave the window, with the observations of the tracks in use.
class KeyframeArchive {
 public:
  void add(const ArchivedKeyframe& keyframe, const std::vector<ArchivedObservation>& observations);
  /// The newest keyframe gets no IMU factor to the next one (after a reset).
  void breakChain();
  void clear() {
    keyframes_.clear();
    tracks_.clear();
  }
  size_t size() const { return keyframes_.size(); }
  /// The keyframes' body poses (after BatchRefinement::solve(): refined).
  std::vector<StateEstimate> trajectory() const;

 private:
  friend class BatchRefinement;
  std::deque<ArchivedKeyframe> keyframes_;
  std::map<int, FeatureTrack> tracks_;  // by feature id; observations on keyframe ids
};

struct BatchRefinementOptions {
  double weight = 460 / 1.5;  // reprojection and homography weight: virtual_focal / pixel_sigma
  double cauchy_scale = 1.0;
  double gravity = 9.81;
  int max_iterations = 50;  // Levenberg–Marquardt; the simulated sequences converge in 5-7
  // The start is the odometry's, near the optimum: little damping at first. With Ceres' default
  // (1e4) the radius shrank on the robust loss' poor model fits and the solve took 14 iterations.
  double initial_trust_region_radius = 1e8;
  // Tracks observed across more keyframes than this keep their inverse depth in the reduced
  // system instead of eliminating it (see solve()).
  int max_eliminated_track_span = 60;
  double min_parallax_rad = 1.0 * M_PI / 180;  // a track's rays must span this to get factors
  size_t min_plane_tracks = 10;                // homography factors on planes with this many
  // calib.ini's [ground] camera_height (m; 0: none) and the window's camera_height_sigma: the
  // keyframes the window held over its ground stay that high over the ground's map plane.
  double camera_height = 0;
  double camera_height_sigma = 0.05;
};

class BatchRefinement {
 public:
  /// `plane_of_label`: the map plane a track's mask label stands for (0: none); `planes`: by map
  /// id, the start (the map's) and, after solve(), the estimate.
  BatchRefinement(KeyframeArchive& archive, const double* mount,
                  const std::function<int(int)>& plane_of_label,
                  std::map<int, PlaneEstimate>& planes, const BatchRefinementOptions& options);
  /// Solves; when the solution is usable, writes it into the archive and the planes, else
  /// returns false and leaves them as they were.
  bool solve();
  /// Summary line for the log.
  const std::string& report() const { return report_; }
  /// IMU-chained keyframe runs solved (each with its own gauge); after solve().
  size_t segments() const { return segments_; }
  /// Tracks whose inverse depth stayed in the reduced system (max_eliminated_track_span).
  size_t longTracks() const { return long_tracks_; }
  /// Wall time of the solve (s).
  double seconds() const { return seconds_; }

 private:
  KeyframeArchive& archive_;
  double mount_[7];
  std::function<int(int)> plane_of_label_;
  std::map<int, PlaneEstimate>& planes_;
  BatchRefinementOptions options_;
  std::string report_;
  size_t segments_ = 0;
  size_t long_tracks_ = 0;
  double seconds_ = 0;
};

}  // namespace rpvio
