#pragma once
// A textured rectangle of the simulated scene (a face of a wall, crate, rack or moving object),
// its ray intersection and its shading under the scene's fixed light.
#include <Eigen/Core>
#include <vector>

#include "sim/mip_texture.h"

namespace rpvio::sim {

/// Direction towards the scene's light (world; lambert shading).
extern const Eigen::Vector3d kLight;

struct ScenePlane {
  int id = 0;
  Eigen::Vector3d origin, u_axis, v_axis, normal;  // rectangle corner, in-plane unit axes, normal
  double width = 0, height = 0;                    // extents along u and v (m)
  float emission = 0;  // > 0: a light panel of this constant radiance (no texture)
  float shade = 1.0f;  // fixed lighting of this face
  MipTexture texture;
  /// World plane n·X = d.
  double distance() const { return normal.dot(origin); }

  /// Where o + t·d meets the front side of the rectangle with t in (1e-9, t_max): t and the
  /// rectangle coordinates (u, v). `numerator` = n·(origin − o), negative when o is in front.
  bool intersectFront(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double numerator,
                      double t_max, double& t, double& u, double& v) const {
    const double denom = normal.dot(d);
    if (denom >= -1e-12) return false;  // back face or parallel
    t = numerator / denom;
    if (t <= 1e-9 || t >= t_max) return false;
    const Eigen::Vector3d local = o + t * d - origin;
    u = local.dot(u_axis), v = local.dot(v_axis);
    return u >= 0 && u <= width && v >= 0 && v <= height;
  }
  /// Shaded, filtered texture at (u, v) hit at ray parameter t along d (same frame as `normal`);
  /// `footprint_per_t`: pixel footprint (m) per unit t.
  float shadeAt(double u, double v, const Eigen::Vector3d& d, double t,
                double footprint_per_t) const;
};

/// A rectangle centred at `centre`, texture seeded by (seed, id).
ScenePlane makeRectangle(int id, const Eigen::Vector3d& centre, const Eigen::Vector3d& normal,
                         const Eigen::Vector3d& u_axis, double width, double height,
                         TextureStyle style, double texel_size, uint64_t seed);

/// The four sides and the top of a box standing on z = base.z() at `base`, turned by `yaw`
/// about z; ids from `next_id` upwards.
void appendBox(std::vector<ScenePlane>& faces, int& next_id, const Eigen::Vector3d& base,
               double yaw, double half_x, double half_y, double height, TextureStyle style,
               double texel_size, uint64_t seed);

}  // namespace rpvio::sim
