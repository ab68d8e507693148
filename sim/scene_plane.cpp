#include "sim/scene_plane.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace rpvio::sim {

const Eigen::Vector3d kLight = Eigen::Vector3d(0.4, 0.3, 0.85).normalized();

float ScenePlane::shadeAt(double u, double v, const Eigen::Vector3d& d, double t,
                          double footprint_per_t) const {
  if (emission > 0) return emission;
  // Footprint grows as the surface tilts away; the square root keeps grazing floors sharp.
  const double cos_incidence = std::abs(normal.dot(d)) / d.norm();
  const double footprint = footprint_per_t * t / std::sqrt(std::max(cos_incidence, 0.05));
  return shade * texture.sample(u, v, footprint);
}

ScenePlane makeRectangle(int id, const Eigen::Vector3d& centre, const Eigen::Vector3d& normal,
                         const Eigen::Vector3d& u_axis, double width, double height,
                         TextureStyle style, double texel_size, uint64_t seed) {
  ScenePlane plane;
  plane.id = id;
  plane.normal = normal.normalized();
  plane.u_axis = u_axis.normalized();
  plane.v_axis = plane.normal.cross(plane.u_axis);  // u × v = n
  plane.width = width;
  plane.height = height;
  plane.origin = centre - 0.5 * width * plane.u_axis - 0.5 * height * plane.v_axis;
  plane.shade = static_cast<float>(0.55 + 0.45 * std::max(0.0, plane.normal.dot(kLight)));
  plane.texture = MipTexture(
      makeSurfaceTexture(width, height, texel_size, style, seed * 257 + static_cast<uint64_t>(id)),
      texel_size);
  return plane;
}

void appendBox(std::vector<ScenePlane>& faces, int& next_id, const Eigen::Vector3d& base,
               double yaw, double half_x, double half_y, double height, TextureStyle style,
               double texel_size, uint64_t seed) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d Z = Eigen::Vector3d::UnitZ();
  const double half[2] = {half_x, half_y};
  for (int side = 0; side < 4; ++side) {
    const int axis = side % 2;
    const double sign = side < 2 ? 1.0 : -1.0;
    const Eigen::Vector3d n = sign * R.col(axis);
    const double width = 2 * half[1 - axis];
    faces.push_back(makeRectangle(next_id++, base + half[axis] * n + 0.5 * height * Z, n,
                                  Z.cross(n), width, height, style, texel_size, seed));
  }
  faces.push_back(makeRectangle(next_id++, base + height * Z, Z, R.col(0), 2 * half_x, 2 * half_y,
                                style, texel_size, seed));
}

}  // namespace rpvio::sim
