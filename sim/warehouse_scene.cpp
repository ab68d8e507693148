#include "sim/warehouse_scene.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

namespace rpvio::sim {

void SceneParams::validate(const OptionsLoader& loader) const {
  loader.require(texel_size > 0, "texel_size", "must be positive");
  loader.require(moving_speed > 0, "moving_speed", "must be positive");
  loader.require(pallet_trucks >= 0 && sliding_panels >= 0 &&
                     pallet_trucks * kPalletTruckFaces + sliding_panels * kSlidingPanelFaces <=
                         kMovingPlaneIdLast - kMovingPlaneIdFirst + 1,
                 "pallet_trucks",
                 "(10 faces each) and sliding_panels (2 faces each) need more than the 40 plane "
                 "ids 200..239");
}

namespace {

// Paths of the moving objects: tangent to these circles around the centre, between the crates
// (up to ~8.5 m) and the characters (10.5 m), in view from anywhere on the flight circle.
constexpr double kTruckRingRadius = 8.75, kTruckAmplitude = 3.5;  // m
constexpr double kPanelRingRadius = 9.5, kPanelAmplitude = 1.5;   // m

/// Back and forth along the tangent of the circle at `angle`, peak speed `speed`.
OscillatingTranslation tangentMotion(double angle, double amplitude, double speed, double phase) {
  OscillatingTranslation m;
  m.axis = Eigen::Vector3d(-std::sin(angle), std::cos(angle), 0);
  m.amplitude = amplitude;
  m.period = 2 * M_PI * amplitude / speed;  // peak speed 2π A / T
  m.phase = phase;
  return m;
}

}  // namespace

WarehouseScene::WarehouseScene(const SceneParams& p) : params_(p) {
  if (p.pallet_trucks * kPalletTruckFaces + p.sliding_panels * kSlidingPanelFaces >
      kMovingPlaneIdLast - kMovingPlaneIdFirst + 1)
    throw std::invalid_argument("too many moving objects for the plane ids 200..239");
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
    appendBox(planes_, next_id, {r * std::cos(angle), r * std::sin(angle), 0}, M_PI * uni(rng),
              0.5 + 0.9 * uni(rng), 0.5 + 0.9 * uni(rng), 1.0 + 2.0 * uni(rng), TextureStyle::Crate,
              p.texel_size, p.seed);
  }
  if (p.racks) {
    for (int wall = 0; wall < 4; ++wall) {
      const double angle = wall * M_PI / 2;
      const Eigen::Vector3d centre =
          (L - 1.0) * Eigen::Vector3d(std::cos(angle), std::sin(angle), 0);
      appendBox(planes_, next_id, centre, angle, 0.6, 6.0 + 2.0 * uni(rng), 3.5 + uni(rng),
                TextureStyle::Shelf, p.texel_size, p.seed);
    }
  }
  addLightPanels();
  for (int k = 0; k < p.characters; ++k) {
    const double angle = 2 * M_PI * k / p.characters + 0.4;
    const Eigen::Vector2d base =
        p.character_ring_radius * Eigen::Vector2d(std::cos(angle), std::sin(angle));
    characters_.push_back(Character::paperDancer(base, 1.7 * k, p.character_height,
                                                 static_cast<int>(p.seed) * 13 + k));
  }
  int moving_id = kMovingPlaneIdFirst;
  for (int k = 0; k < p.pallet_trucks; ++k)
    addPalletTruck(moving_id, 2 * M_PI * k / p.pallet_trucks + 1.9, 1.3 * k + 0.5);
  for (int k = 0; k < p.sliding_panels; ++k)
    addSlidingPanel(moving_id, 2 * M_PI * k / p.sliding_panels + 3.6, 2.1 * k + 1.0);
}

void WarehouseScene::addRectangle(int id, const Eigen::Vector3d& centre,
                                  const Eigen::Vector3d& normal, const Eigen::Vector3d& u_axis,
                                  double width, double height, TextureStyle style) {
  planes_.push_back(makeRectangle(id, centre, normal, u_axis, width, height, style,
                                  params_.texel_size, params_.seed));
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

void WarehouseScene::addPalletTruck(int& next_id, double angle, double phase) {
  // Driving along the tangent: a load of boxes (1.2 x 1.0 x 1.5 m) ahead of the driver's unit.
  const double yaw = angle + M_PI / 2;
  const Eigen::Vector3d ahead(std::cos(yaw), std::sin(yaw), 0);
  std::vector<ScenePlane> faces;
  appendBox(faces, next_id, 0.3 * ahead, yaw, 0.6, 0.5, 1.5, TextureStyle::Crate,
            params_.texel_size, params_.seed);
  appendBox(faces, next_id, -0.75 * ahead, yaw, 0.3, 0.45, 1.3, TextureStyle::Crate,
            params_.texel_size, params_.seed);
  const Eigen::Vector3d centre(kTruckRingRadius * std::cos(angle),
                               kTruckRingRadius * std::sin(angle), 0);
  moving_.emplace_back(std::move(faces), centre,
                       tangentMotion(angle, kTruckAmplitude, params_.moving_speed, phase));
}

void WarehouseScene::addSlidingPanel(int& next_id, double angle, double phase) {
  // A 3 m x 2.5 m panel facing the centre, sliding along its width; textured on both sides.
  const Eigen::Vector3d radial(std::cos(angle), std::sin(angle), 0), Z = Eigen::Vector3d::UnitZ();
  std::vector<ScenePlane> faces;
  for (const Eigen::Vector3d& n : {Eigen::Vector3d(-radial), radial})
    faces.push_back(makeRectangle(next_id++, 1.25 * Z, n, Z.cross(n), 3.0, 2.5, TextureStyle::Crate,
                                  params_.texel_size, params_.seed));
  moving_.emplace_back(std::move(faces), kPanelRingRadius * radial,
                       tangentMotion(angle, kPanelAmplitude, params_.moving_speed, phase));
}

void WarehouseScene::setTime(double t) {
  for (auto& c : characters_) c.pose(t);
  for (auto& m : moving_) m.setTime(t);
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
  for (size_t k = 0; k < characters_.size(); ++k)
    if (characters_[k].onStage()) view.characters.emplace_back(k, ~0ULL);
  return view;
}

WarehouseScene::PlanesInView WarehouseScene::cullToPyramid(
    const PlanesInView& view, const std::array<Eigen::Vector3d, 4>& directions) const {
  // Inward normals of the pyramid's sides: a point X is outside side i when n_i·(X − o) < 0.
  const Eigen::Vector3d middle = directions[0] + directions[1] + directions[2] + directions[3];
  std::array<Eigen::Vector3d, 4> sides;
  for (int i = 0; i < 4; ++i) {
    sides[i] = directions[i].cross(directions[(i + 1) % 4]).normalized();
    if (sides[i].dot(middle) < 0) sides[i] = -sides[i];
  }
  const Eigen::Vector3d& o = view.origin;
  PlanesInView culled;
  culled.origin = o;
  for (const auto& entry : view.planes) {
    const ScenePlane& p = *entry.first;
    const Eigen::Vector3d u = p.width * p.u_axis, v = p.height * p.v_axis;
    const Eigen::Vector3d corners[4] = {p.origin - o, p.origin + u - o, p.origin + u + v - o,
                                        p.origin + v - o};
    bool outside = false;
    for (const Eigen::Vector3d& n : sides) {
      outside = std::all_of(std::begin(corners), std::end(corners),
                            [&](const Eigen::Vector3d& x) { return n.dot(x) < -1e-9; });
      if (outside) break;
    }
    if (!outside) culled.planes.push_back(entry);
  }
  for (const auto& [k, parts] : view.characters) {
    const uint64_t inside = parts & characters_[k].figure().partsInPyramid(o, sides);
    if (inside) culled.characters.emplace_back(k, inside);
  }
  return culled;
}

SceneHit WarehouseScene::cast(const PlanesInView& view, const Eigen::Vector3d& d,
                              double footprint_per_t) const {
  const Eigen::Vector3d& o = view.origin;
  SceneHit hit;
  hit.t = INFINITY;
  const ScenePlane* best = nullptr;
  double best_u = 0, best_v = 0;
  for (const auto& [plane, numerator] : view.planes) {
    double t, u, v;
    if (plane->intersectFront(o, d, numerator, hit.t, t, u, v))
      hit.t = t, best = plane, best_u = u, best_v = v;
  }
  for (size_t k = 0; k < moving_.size(); ++k) {
    if (auto h = moving_[k].intersect(o, d, hit.t, footprint_per_t)) {
      hit.moving_object = static_cast<int>(k);
      hit.t = h->t;
      hit.point = h->point;
      hit.label = h->id;
      hit.dynamic = true;
      hit.intensity = h->intensity;
      best = nullptr;
    }
  }
  for (const auto& [k, parts] : view.characters) {
    if (auto c = characters_[k].intersect(o, d, hit.t, parts)) {
      hit.t = c->t;
      hit.point = c->point;
      hit.label = kMaskCharacter;
      hit.character = static_cast<int>(k);
      hit.part = c->part;
      hit.moving_object = -1;
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
    hit.moving_object = -1;
    hit.intensity = best->shadeAt(best_u, best_v, d, hit.t, footprint_per_t);
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
