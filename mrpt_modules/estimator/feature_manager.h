#pragma once
// The sliding window's feature tracks (VINS-Mono §IV-C): each track is anchored at its first
// observation in the window and parametrized by its inverse depth in that camera. Tracks are
// triangulated from the window's poses, re-anchored (depth transferred) when their anchor frame
// leaves the window, and forgotten when no observation is left.
#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <vector>

#include "mrpt_modules/core/feature_frame.h"

namespace rpvio {

struct TrackObservation {
  uint64_t frame = 0;  // window frame id
  Eigen::Vector2d normalized = Eigen::Vector2d::Zero();
};

struct FeatureTrack {
  int id = -1;
  int plane_id = 0;
  std::vector<TrackObservation> observations;  // oldest first; front() is the anchor
  double inv_depth[1] = {0};                   // in the anchor camera; parameter block
  bool triangulated = false;
};

/// Camera pose in the world of a window frame, by frame id.
using CameraPoseLookup = std::function<Eigen::Isometry3d(uint64_t frame)>;

/// Widest angle between the anchor's ray and another observation's, in the world frame (rad).
double widestRayAngle(const FeatureTrack& track, const CameraPoseLookup& cameras);
/// Depth in the anchor camera of the linear triangulation from all the track's observations;
/// nothing when degenerate.
std::optional<double> linearAnchorDepth(const FeatureTrack& track, const CameraPoseLookup& cameras);

class FeatureManager {
 public:
  /// Adds the observations of a new window frame.
  void addFrame(uint64_t frame, const FeatureFrame& features);
  /// Drops the observations of `frame`; tracks anchored there are re-anchored at their next
  /// observation with the depth transferred (`cameras` must still know `frame`).
  void removeFrame(uint64_t frame, const CameraPoseLookup& cameras);
  /// Triangulates (linear, all observations) the tracks not yet triangulated with at least two
  /// observations whose rays differ by `min_angle_rad`; depths outside (min, max) are rejected.
  void triangulate(const CameraPoseLookup& cameras, double min_angle_rad, double min_depth,
                   double max_depth);
  /// Forgets a track's depth (e.g. behind the camera after an optimization).
  void untriangulate(FeatureTrack& track) { track.triangulated = false; }
  /// World point of a triangulated track.
  Eigen::Vector3d worldPoint(const FeatureTrack& track, const CameraPoseLookup& cameras) const;

  std::map<int, FeatureTrack>& tracks() { return tracks_; }
  const std::map<int, FeatureTrack>& tracks() const { return tracks_; }
  void clear() { tracks_.clear(); }

 private:
  std::map<int, FeatureTrack> tracks_;  // by feature id (ordered: deterministic iteration)
};

}  // namespace rpvio
