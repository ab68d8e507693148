#pragma once
#include <vector>

#include "planes_map/plane.h"
#include "sim/warehouse_scene.h"

namespace rpvio::apps {
/// rpvio-sim: renders simulated warehouse sequences (see sim/).
int simMain(int argc, char** argv);

/// The scene's planes as a plane map (id and mask label = the plane's mask label, polygon = its
/// rectangle, certain, seen until `duration`), for evaluating estimated plane maps; the faces of
/// moving objects at t = 0, `moving` with their motion.
std::vector<Plane> truePlanes(const sim::WarehouseScene& scene, double duration);
}  // namespace rpvio::apps
