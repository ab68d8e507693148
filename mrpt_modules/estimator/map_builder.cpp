#include "mrpt_modules/estimator/map_builder.h"

namespace rpvio {

void MapBuilder::planesSeen(const PlanesSeen& planes) {
  for (const PlaneObservation& o : planes.planes) map_.update(o);
}

void MapBuilder::keyframeLeft(const KeyframeLeft& keyframe) {
  if (options_.batch_refinement) archive_.add(keyframe.keyframe, keyframe.observations);
}

void MapBuilder::windowFinished(const WindowFinished& end) {
  map_.mergeDuplicates();
  if (options_.batch_refinement) refine(end);
}

void MapBuilder::refine(const WindowFinished& end) {
  if (archive_.size() < 2) return;  // never initialized
  if (archive_.size() > options_.batch_refinement_max_keyframes) {
    refinement_report_ = "batch refinement skipped: " + std::to_string(archive_.size()) +
                         " keyframes, more than batch_refinement_max_keyframes (" +
                         std::to_string(options_.batch_refinement_max_keyframes) + ")";
    return;
  }
  std::map<int, PlaneEstimate> planes;
  for (const Plane& p : map_.confirmedPlanes()) {
    PlaneEstimate& r = planes[p.id];
    std::copy(p.normal.data(), p.normal.data() + 3, r.normal);
    r.distance[0] = p.distance;
  }
  BatchRefinement batch(
      archive_, end.mount,
      [this](int label) {
        const Plane* p = map_.planeOfMask(label);
        return p ? p->id : 0;
      },
      planes, end.refinement);
  const bool solved = batch.solve();
  refinement_report_ = batch.report();
  refinement_seconds_ = batch.seconds();
  if (!solved) {
    refinement_report_ += " (not usable: the map and trajectory keep the odometry's)";
    return;
  }
  for (const auto& [id, r] : planes)
    map_.setParameters(id, Eigen::Vector3d(r.normal).normalized(), r.distance[0]);
  refined_trajectory_ = archive_.trajectory();
}

}  // namespace rpvio
