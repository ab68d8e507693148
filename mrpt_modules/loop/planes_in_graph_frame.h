#pragma once
// The plane map follows the loop closure: a plane is moved by the pose graph's correction at the
// keyframe nearest to when it was first seen (the time its parameters come from: seen again later,
// the estimator takes them back from the map), and a saved map's planes are merged with a run's.
#include <Eigen/Geometry>
#include <utility>
#include <vector>

#include "planes_map/planes_map.h"

namespace rpvio {

/// (keyframe time, graph correction: the odometry's world onto the graph's), sorted by time.
using KeyframeCorrections = std::vector<std::pair<double, Eigen::Isometry3d>>;

/// `planes` moved into the graph's frame; unmoved without corrections.
std::vector<Plane> planesInGraphFrame(const std::vector<Plane>& planes,
                                      const KeyframeCorrections& corrections);

/// `base` with `added` merged in, plane by plane (PlanesMap::addPlane): both in one frame.
std::vector<Plane> mergedPlanes(const std::vector<Plane>& base, const std::vector<Plane>& added);

}  // namespace rpvio
