#pragma once
// The planes of the sliding window (DESIGN.md §1 step 4): which ones get homography factors (none,
// the largest with hysteresis, or all), their parameters when they enter (the planes map's when it
// knows the label, else a least-squares fit of their triangulated features), and what the window
// hands the map.
#include <ceres/problem.h>

#include <map>
#include <set>
#include <vector>

#include "mrpt_modules/estimator/estimator_options.h"
#include "mrpt_modules/estimator/estimator_types.h"
#include "mrpt_modules/estimator/feature_manager.h"
#include "planes_map/planes_map.h"

namespace rpvio {

/// A plane enters the window, gets homography factors and goes to the map with this many tracks
/// in use (fewer leave directions of (n, d) unobserved, which a solve then moves at will).
constexpr size_t kMinPlanePoints = 10;

/// A track in the optimization: triangulated and observed at least twice.
inline bool inUse(const FeatureTrack& track) {
  return track.triangulated && track.observations.size() >= 2;
}

class WindowPlanes {
 public:
  explicit WindowPlanes(HomographyPlanes which) : which_(which) {}

  /// By mask label: the planes with parameters in the window.
  PlaneEstimates& estimates() { return planes_; }
  const PlaneEstimates& estimates() const { return planes_; }
  /// The labels whose features get homography factors: none, every plane, or the one with most
  /// tracks, kept while it has 70% of the best count; among `eligible` only, if given.
  void choose(const FeatureManager& features, const std::set<int>* eligible = nullptr);
  const std::set<int>& chosen() const { return used_; }
  /// Parameters for the chosen planes without: the map's entry of the label, else a fit of the
  /// plane's triangulated features (seen 3 times, the ground's twice) when at least kMinPlanePoints
  /// and planar within kMaxPlaneRmsPerDepth of their distance to the newest camera.
  void initialize(const FeatureManager& features, const CameraPoseLookup& cameras,
                  const Eigen::Vector3d& newest_camera, const PlanesMap& map);
  /// Labels with kMinPlanePoints tracks in use or more.
  std::set<int> constrained(const FeatureManager& features) const;
  /// The plane whose homography factors the track's observations get (chosen and one of
  /// `constrained`), or nullptr.
  PlaneEstimate* homographyPlane(const FeatureTrack& track, const std::set<int>& constrained);
  /// The planes of a new window (the initializer's).
  void start(const std::map<int, WorldPlane>& planes);
  /// Each plane with at least kMinPlanePoints triangulated points, for the map (stamped t).
  std::vector<PlaneObservation> observations(const FeatureManager& features,
                                             const CameraPoseLookup& cameras, double t) const;
  /// For the map only, the planes without parameters in the window (among `eligible` if given):
  /// a fit of each one's triangulated features as `initialize` makes, with its covariance for
  /// the number of points. A label's observations while it stays in the window are one visit.
  std::vector<PlaneObservation> fittedObservations(const FeatureManager& features,
                                                   const CameraPoseLookup& cameras, double t,
                                                   const Eigen::Vector3d& newest_camera,
                                                   const std::set<int>* eligible);
  /// The chosen planes' covariances of (n, d) from the solved `problem` (the window's marginal
  /// covariance on the sphere, moved to ambient (n, d), plus the drift between visits); a plane
  /// keeps its last one when the problem cannot give it (then false, as with no plane).
  bool updateCovariances(ceres::Problem& problem, const std::set<int>& planes);
  void clear() {
    planes_.clear();
    used_.clear();
    largest_ = -1;
    fitted_visits_.clear();
  }

 private:
  PlaneEstimate newEstimate(const double* normal, double distance);

  HomographyPlanes which_;
  PlaneEstimates planes_;
  std::set<int> used_;   // labels whose features get homography factors
  int largest_ = -1;     // with kLargest: the plane chosen as the largest
  uint64_t visits_ = 0;  // planes that entered the window so far (estimated or fitted)
  std::map<int, uint64_t> fitted_visits_;  // label → visit, of the last fittedObservations
};

}  // namespace rpvio
