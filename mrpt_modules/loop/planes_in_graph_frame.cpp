#include "mrpt_modules/loop/planes_in_graph_frame.h"

#include <algorithm>
#include <iterator>

namespace rpvio {

std::vector<Plane> planesInGraphFrame(const std::vector<Plane>& planes,
                                      const KeyframeCorrections& corrections) {
  if (corrections.empty()) return planes;
  std::vector<Plane> moved;
  for (const Plane& plane : planes) {
    const auto after =
        std::lower_bound(corrections.begin(), corrections.end(), plane.first_seen,
                         [](const auto& correction, double t) { return correction.first < t; });
    auto nearest = after;
    if (after == corrections.end() ||
        (after != corrections.begin() &&
         plane.first_seen - std::prev(after)->first < after->first - plane.first_seen))
      nearest = std::prev(after);
    moved.push_back(plane.transformed(nearest->second));
  }
  return moved;
}

std::vector<Plane> mergedPlanes(const std::vector<Plane>& base, const std::vector<Plane>& added) {
  PlanesMap map;
  const auto withSupport = [&](Plane p) {
    if (p.support.empty()) p.supportFromPolygon(map.options().voxel_size_m);
    return p;
  };
  // The base is one map already: its planes are kept apart.
  for (const Plane& p : base) map.addPlane(withSupport(p), false);
  for (const Plane& p : added) map.addPlane(withSupport(p));
  return map.planes();
}

}  // namespace rpvio
