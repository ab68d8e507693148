#pragma once
// What the sliding-window estimator hands on about the map as keyframes leave its window, and the
// map it takes known planes from: the map builder (map_builder.h) takes it directly; in a pipeline
// the estimator module publishes it as messages to the MapBuilderModule.
#include <string>
#include <vector>

#include "mrpt_modules/estimator/batch_refinement.h"
#include "planes_map/planes_map.h"

namespace rpvio {

/// A keyframe leaving the window (marginalized, or at the end of the run), with the observations
/// it holds of the tracks in use.
struct KeyframeLeft {
  ArchivedKeyframe keyframe;
  std::vector<ArchivedObservation> observations;
};

/// The window's planes, as the map should know them now (a keyframe leaves; the run ends).
struct PlanesSeen {
  std::vector<PlaneObservation> planes;
};

/// A reset: the keyframe that left last has no IMU link to the next one.
struct KeyframeChainBroken {};
/// A re-initialization not placed in the old world: the keyframes so far are in another one.
struct NewWorld {};
/// The run ended and every keyframe has left: the map's duplicates merge and the batch
/// refinement solves, with the window's factor weights and camera mount.
struct WindowFinished {
  BatchRefinementOptions refinement;
  double mount[7] = {0, 0, 0, 0, 0, 0, 1};  // T_BC as a pose block
};

/// Published by the map builder module when its map is set up: the map the estimator takes known
/// planes from.
struct MapReady {
  const PlanesMap* planes_map = nullptr;
};

/// Published by the map builder module at the end of the run: the finished map.
struct MapSummary {
  const PlanesMap* planes_map = nullptr;
  std::vector<StateEstimate> refined_trajectory;  // keyframes; empty without a refinement
  std::string refinement_report;                  // "" if it did not run
  double refinement_s = 0;
};

class MapSink {
 public:
  virtual ~MapSink() = default;
  /// The map planes are taken from when a label is seen again.
  virtual const PlanesMap& planesMap() const = 0;
  virtual void planesSeen(const PlanesSeen& planes) = 0;
  virtual void keyframeLeft(const KeyframeLeft& keyframe) = 0;
  virtual void chainBroken() = 0;
  virtual void newWorld() = 0;
  virtual void windowFinished(const WindowFinished& end) = 0;
};

}  // namespace rpvio
