#include "sim/warehouse_scene.h"

#include <Eigen/Geometry>
#include <cmath>
#include <random>

namespace rpvio::sim {
namespace {

const Eigen::Vector3d kLight = Eigen::Vector3d(0.4, 0.3, 0.85).normalized();

float lambert(const Eigen::Vector3d& normal) {
  return static_cast<float>(0.55 + 0.45 * std::max(0.0, normal.dot(kLight)));
}

}  // namespace

WarehouseScene::WarehouseScene(const SceneParams& p) : params_(p) {
  const double L = p.room_half_size, H = p.room_height;
  const Eigen::Vector3d X = Eigen::Vector3d::UnitX(), Y = Eigen::Vector3d::UnitY(),
                        Z = Eigen::Vector3d::UnitZ();
  addRectangle(1, {0, 0, 0}, Z, X, 2 * L, 2 * L, TextureStyle::Floor);
  addRectangle(2, {L, 0, H / 2}, -X, -Y, 2 * L, H, TextureStyle::Wall);
  addRectangle(3, {0, L, H / 2}, -Y, X, 2 * L, H, TextureStyle::Wall);
  addRectangle(4, {-L, 0, H / 2}, X, Y, 2 * L, H, TextureStyle::Wall);
  addRectangle(5, {0, -L, H / 2}, Y, -X, 2 * L, H, TextureStyle::Wall);
  if (p.ceiling) addRectangle(6, {0, 0, H}, -Z, Y, 2 * L, 2 * L, TextureStyle::Wall);

  std::mt19937_64 rng(p.seed * 1000003 + 17);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  int next_id = 10;
  for (int k = 0; k < p.crates; ++k) {
    const double angle = 2 * M_PI * (k + 0.3 * uni(rng)) / std::max(1, p.crates);
    const double r = p.crate_ring_min + (p.crate_ring_max - p.crate_ring_min) * uni(rng);
    addBox(next_id, {r * std::cos(angle), r * std::sin(angle)}, M_PI * uni(rng),
           0.5 + 0.9 * uni(rng), 0.5 + 0.9 * uni(rng), 1.0 + 2.0 * uni(rng), TextureStyle::Crate);
  }
  if (p.racks) {
    for (int wall = 0; wall < 4; ++wall) {
      const double angle = wall * M_PI / 2;
      const Eigen::Vector2d centre = (L - 1.0) * Eigen::Vector2d(std::cos(angle), std::sin(angle));
      addBox(next_id, centre, angle, 0.6, 6.0 + 2.0 * uni(rng), 3.5 + uni(rng),
             TextureStyle::Shelf);
    }
  }
  addLightPanels();
  for (int k = 0; k < p.characters; ++k) {
    const double angle = 2 * M_PI * k / p.characters + 0.4;
    const Eigen::Vector2d base =
        p.character_ring_radius * Eigen::Vector2d(std::cos(angle), std::sin(angle));
    characters_.emplace_back(base, 1.7 * k, p.character_height, static_cast<int>(p.seed) * 13 + k);
  }
}

void WarehouseScene::addRectangle(int id, const Eigen::Vector3d& centre,
                                  const Eigen::Vector3d& normal, const Eigen::Vector3d& u_axis,
                                  double width, double height, TextureStyle style) {
  ScenePlane plane;
  plane.id = id;
  plane.normal = normal.normalized();
  plane.u_axis = u_axis.normalized();
  plane.v_axis = plane.normal.cross(plane.u_axis);  // u × v = n
  plane.width = width;
  plane.height = height;
  plane.origin = centre - 0.5 * width * plane.u_axis - 0.5 * height * plane.v_axis;
  plane.shade = lambert(plane.normal);
  plane.texture = MipTexture(makeSurfaceTexture(width, height, params_.texel_size, style,
                                                params_.seed * 257 + static_cast<uint64_t>(id)),
                             params_.texel_size);
  planes_.push_back(std::move(plane));
}

void WarehouseScene::addLightPanels() {
  constexpr int kFirstId = 180, kMaxPanels = 20, kPerWall = 5;
  const int walls[4] = {4, 5, 2, 3};                     // wall 4 faces the start of the flight
  const double offsets[kPerWall] = {0, -8, 8, -16, 16};  // m along the wall from its middle
  const double H = params_.room_height;
  for (int k = 0; k < std::min(params_.light_panels, kMaxPanels); ++k) {
    const ScenePlane& wall = *plane(walls[k / kPerWall]);
    // 6 m x 3.5 m, above the racks (<= 4.5 m), 1 cm in front of the wall.
    const Eigen::Vector3d centre = wall.origin +
                                   (0.5 * wall.width + offsets[k % kPerWall]) * wall.u_axis +
                                   0.65 * H * Eigen::Vector3d::UnitZ() + 0.01 * wall.normal;
    ScenePlane panel;
    panel.id = kFirstId + k;
    panel.normal = wall.normal;
    panel.u_axis = wall.u_axis;
    panel.v_axis = wall.v_axis;
    panel.width = 6.0;
    panel.height = 3.5;
    panel.origin = centre - 0.5 * panel.width * panel.u_axis - 0.5 * panel.height * panel.v_axis;
    panel.emission = static_cast<float>(params_.light_intensity);
    planes_.push_back(std::move(panel));
  }
}

void WarehouseScene::addBox(int& next_id, const Eigen::Vector2d& c, double yaw, double half_x,
                            double half_y, double height, TextureStyle style) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d centre(c.x(), c.y(), 0), Z = Eigen::Vector3d::UnitZ();
  const double half[2] = {half_x, half_y};
  for (int side = 0; side < 4; ++side) {
    const int axis = side % 2;
    const double sign = side < 2 ? 1.0 : -1.0;
    const Eigen::Vector3d n = sign * R.col(axis);
    const double width = 2 * half[1 - axis];
    addRectangle(next_id++, centre + half[axis] * n + 0.5 * height * Z, n, Z.cross(n), width,
                 height, style);
  }
  addRectangle(next_id++, centre + height * Z, Z, R.col(0), 2 * half_x, 2 * half_y, style);
}

void WarehouseScene::setTime(double t) {
  for (auto& c : characters_) c.pose(t);
}

WarehouseScene::PlanesInView WarehouseScene::planesInView(const Eigen::Vector3d& origin) const {
  PlanesInView view;
  view.origin = origin;
  for (const ScenePlane& p : planes_) {
    // A plane the origin is behind (or on) gives t = numerator / denom <= 0 for every ray that
    // meets its front side (denom < 0): never a hit.
    const double numerator = p.normal.dot(p.origin - origin);
    if (numerator < 0) view.planes.emplace_back(&p, numerator);
  }
  return view;
}

SceneHit WarehouseScene::cast(const PlanesInView& view, const Eigen::Vector3d& d,
                              double footprint_per_t) const {
  const Eigen::Vector3d& o = view.origin;
  SceneHit hit;
  hit.t = INFINITY;
  const ScenePlane* best = nullptr;
  double best_u = 0, best_v = 0;
  for (const auto& [plane, numerator] : view.planes) {
    const ScenePlane& p = *plane;
    const double denom = p.normal.dot(d);
    if (denom >= -1e-12) continue;  // back face or parallel
    const double t = numerator / denom;
    if (t <= 1e-9 || t >= hit.t) continue;
    const Eigen::Vector3d local = o + t * d - p.origin;
    const double u = local.dot(p.u_axis), v = local.dot(p.v_axis);
    if (u < 0 || u > p.width || v < 0 || v > p.height) continue;
    hit.t = t, best = &p, best_u = u, best_v = v;
  }
  for (size_t k = 0; k < characters_.size(); ++k) {
    if (auto c = characters_[k].intersect(o, d, hit.t)) {
      hit.t = c->t;
      hit.point = c->point;
      hit.label = kMaskCharacter;
      hit.character = static_cast<int>(k);
      hit.dynamic = true;
      hit.intensity =
          c->albedo * (0.4f + 0.6f * static_cast<float>(std::max(0.0, c->normal.dot(kLight))));
      best = nullptr;
    }
  }
  if (best) {
    hit.point = o + hit.t * d;
    hit.label = best->id;
    hit.dynamic = false;
    // Footprint grows as the surface tilts away; the square root keeps grazing floors sharp.
    const double cos_incidence = std::abs(best->normal.dot(d)) / d.norm();
    const double footprint = footprint_per_t * hit.t / std::sqrt(std::max(cos_incidence, 0.05));
    hit.intensity = best->emission > 0
                        ? best->emission
                        : best->shade * best->texture.sample(best_u, best_v, footprint);
    for (const DiscMarker& m : params_.markers)
      if ((hit.point - m.centre).squaredNorm() <= m.radius * m.radius) hit.intensity = m.intensity;
  }
  if (!std::isfinite(hit.t)) hit.t = 0;
  return hit;
}

double WarehouseScene::distanceToCharacters(const Eigen::Vector3d& x) const {
  double best = INFINITY;
  for (const auto& c : characters_) best = std::min(best, c.signedDistance(x));
  return best;
}

const ScenePlane* WarehouseScene::plane(int id) const {
  for (const auto& p : planes_)
    if (p.id == id) return &p;
  return nullptr;
}

}  // namespace rpvio::sim
