#pragma once
// The map beyond the sliding window: the persistent planes map (planes seen again get their entry
// back), the archive of every keyframe that left the window, and the batch refinement over them at
// the end of the run (batch_refinement.h). Options: MapBuilderOptions, and the planes map's.
#include <string>
#include <vector>

#include "common/options.h"
#include "mrpt_modules/estimator/map_sink.h"

namespace rpvio {

struct MapBuilderOptions {
  // At the end of a run, one bundle adjustment over all keyframes: the plane map's final (n, d)
  // and trajectory_refined.tum. The keyframes' observations are kept until then (memory grows
  // with the keyframes) ...
  bool batch_refinement = true;
  // ... and it is skipped (and said so) beyond this many keyframes.
  size_t batch_refinement_max_keyframes = 2000;

  template <class Visitor>
  void fields(Visitor& v) {
    RPVIO_OPTION(v, batch_refinement);
    RPVIO_OPTION(v, batch_refinement_max_keyframes);
  }
};

class MapBuilder : public MapSink {
 public:
  MapBuilder(const PlanesMapOptions& map_options, const MapBuilderOptions& options)
      : map_(map_options), options_(options) {}

  const PlanesMap& planesMap() const override { return map_; }
  void planesSeen(const PlanesSeen& planes) override;
  void keyframeLeft(const KeyframeLeft& keyframe) override;
  void chainBroken() override { archive_.breakChain(); }
  void newWorld() override { archive_.clear(); }
  /// Merges the map's duplicates (a plane whose visit started too far from its entry to be
  /// associated got a new one; their estimates have converged since), then the batch refinement.
  void windowFinished(const WindowFinished& end) override;

  /// After windowFinished(): the keyframes' body poses from the batch refinement (empty if it did
  /// not run or failed), its summary ("" if it did not run) and time.
  const std::vector<StateEstimate>& refinedTrajectory() const { return refined_trajectory_; }
  const std::string& refinementReport() const { return refinement_report_; }
  double refinementSeconds() const { return refinement_seconds_; }

 private:
  void refine(const WindowFinished& end);

  PlanesMap map_;
  MapBuilderOptions options_;
  KeyframeArchive archive_;
  std::vector<StateEstimate> refined_trajectory_;
  std::string refinement_report_;
  double refinement_seconds_ = 0;
};

}  // namespace rpvio
