// Fuzzes the plane map reader (planes_map/plane_map_exporters.h: readPlanesYaml, as rpvio-eval
// reads an estimated and a ground-truth planes.yaml): keys, flow lists of numbers, the motion of
// moving planes. The planes it returns must hold finite numbers only.
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "planes_map/plane_map_exporters.h"
#include "tests/fuzz/fuzz_util.h"

using namespace rpvio;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const fuzz::InputFile file(data, size, "planes.yaml");
  fuzz::readExpectingOnlyInputError([&] {
    for (const Plane& p : readPlanesYaml(file.path())) {
      bool finite = p.normal.allFinite() && std::isfinite(p.distance) && p.covariance.allFinite() &&
                    std::isfinite(p.first_seen) && std::isfinite(p.last_seen) &&
                    p.motion.axis.allFinite() && std::isfinite(p.motion.amplitude) &&
                    std::isfinite(p.motion.period) && std::isfinite(p.motion.phase);
      for (const Eigen::Vector3d& x : p.polygon) finite = finite && x.allFinite();
      fuzz::require(finite, "plane with a number that is not finite");
    }
  });
  return 0;
}
