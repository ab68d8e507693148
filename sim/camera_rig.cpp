#include "sim/camera_rig.h"

#include <cmath>

namespace rpvio::sim {

PinholeCamera CameraRig::intrinsics() const {
  PinholeCamera c;
  c.width = width;
  c.height = height;
  c.fx = c.fy = 0.5 * width / std::tan(0.5 * hfov_deg * M_PI / 180);
  c.cx = 0.5 * (width - 1);
  c.cy = 0.5 * (height - 1);
  return c;
}

Eigen::Isometry3d CameraRig::T_BC() const {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() << 0, 0, 1,  //
      -1, 0, 0,           //
      0, -1, 0;           // columns: camera x, y, z axes in the body frame
  T.translation() = T_BC_translation;
  return T;
}

}  // namespace rpvio::sim
