#pragma once
// The simulated camera as the scene file's [camera] section gives it: image size, horizontal field
// of view (principal point at the image centre) and where it sits on the body.
#include <Eigen/Geometry>

#include "common/options.h"
#include "sim/renderer.h"

namespace rpvio::sim {

struct CameraRig {
  int width = 640, height = 480;                      // px
  double hfov_deg = 90;                               // deg; fx = fy = width / (2 tan(hfov / 2))
  Eigen::Vector3d T_BC_translation{0.10, 0.0, 0.05};  // m, camera centre in the body frame

  template <class Visitor>
  void fields(Visitor& v) {
    RPVIO_OPTION(v, width);
    RPVIO_OPTION(v, height);
    RPVIO_OPTION(v, hfov_deg);
    RPVIO_OPTION(v, T_BC_translation);
  }
  void validate(const OptionsLoader& loader) const {
    loader.require(width > 0, "width", "must be positive");
    loader.require(height > 0, "height", "must be positive");
    loader.require(hfov_deg > 0 && hfov_deg < 180, "hfov_deg", "must be between 0 and 180");
  }
  PinholeCamera intrinsics() const;
  /// The camera looks along body x: camera z = body x, camera x = −body y, camera y = −body z.
  Eigen::Isometry3d T_BC() const;
};

}  // namespace rpvio::sim
