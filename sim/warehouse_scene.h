#pragma once
// The simulated warehouse: a closed room (floor, four walls, optional ceiling), crates inside the
// flight circle, racks along the walls — every visible face a textured rectangle with its own,
// stable plane id — characters (the paper's dancers around the circle's centre, or a crowd
// given by setCharacters, sim/crowd.h), and optional moving planar objects (pallet trucks
// carrying boxes, sliding panels) driving back and forth inside the circle, and optional light
// panels (windows high on the walls, far brighter than the surfaces: they saturate the 8-bit
// image).
//
// Plane ids: floor 1, walls 2..5, ceiling 6, then crate and rack faces from 10 upwards (below 100:
// the mask degradation's split plane takes id + 100); light panels 180..199; faces of moving
// objects 200..239.
// Mask labels: plane id on static planes and on moving faces (as a CNN labels them; the renderer's
// `dynamic` image tells them apart), 0 on characters, 255 where the ray hits nothing.
#include <Eigen/Core>
#include <array>
#include <memory>
#include <utility>
#include <vector>

#include "common/options.h"
#include "sim/character.h"
#include "sim/moving_planar_object.h"
#include "sim/scene_plane.h"

namespace rpvio::sim {

constexpr int kMaskCharacter = 0;
constexpr int kMaskNothing = 255;
constexpr int kMovingPlaneIdFirst = 200, kMovingPlaneIdLast = 239;
constexpr int kPalletTruckFaces = 10, kSlidingPanelFaces = 2;

/// A flat disc painted on a surface (tests measure where the renderer draws it).
struct DiscMarker {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // world, on a plane
  double radius = 0.1;                               // m
  float intensity = 255;
};

struct SceneParams {
  double room_half_size = 20.0;  // m, walls at x, y = ±half size
  double room_height = 10.0;     // m
  bool ceiling = true;
  int crates = 8;                                     // inside the flight circle
  double crate_ring_min = 3.0, crate_ring_max = 6.5;  // m from the centre
  bool racks = true;                                  // along the walls
  double texel_size = 0.02;                           // m per texture texel
  int characters = 0;  // the paper's dancers on a ring (unless setCharacters replaces them)
  double character_ring_radius = 10.5;  // m; < 15 sin 45°: in the 90° view from the circle
  double character_height = 1.8;        // m
  int light_panels = 0;                 // windows, on wall 4 (seen at the start) first, 5 per wall
  double light_intensity = 2000;        // radiance of the panels (surfaces are 0..255)
  int pallet_trucks = 0;                // moving planar objects (ids 200..239: at most 40 faces)
  int sliding_panels = 0;
  double moving_speed = 1.5;        // m/s, peak speed of trucks and panels
  uint64_t seed = 1;                // [sequence] seed
  std::vector<DiscMarker> markers;  // tests only

  template <class Visitor>
  void fields(Visitor& v) {  // characters and seed are [sequence] keys
    RPVIO_OPTION(v, room_half_size);
    RPVIO_OPTION(v, room_height);
    RPVIO_OPTION(v, ceiling);
    RPVIO_OPTION(v, crates);
    RPVIO_OPTION(v, crate_ring_min);
    RPVIO_OPTION(v, crate_ring_max);
    RPVIO_OPTION(v, racks);
    RPVIO_OPTION(v, texel_size);
    RPVIO_OPTION(v, character_ring_radius);
    RPVIO_OPTION(v, character_height);
    RPVIO_OPTION(v, light_panels);
    RPVIO_OPTION(v, light_intensity);
    RPVIO_OPTION(v, pallet_trucks);
    RPVIO_OPTION(v, sliding_panels);
    RPVIO_OPTION(v, moving_speed);
  }
  void validate(const OptionsLoader& loader) const;
};

struct SceneHit {
  double t = 0;  // ray parameter (depth when dir has unit camera z)
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  int label = kMaskNothing;  // plane id, kMaskCharacter or kMaskNothing
  int character = -1;        // index of the character hit, if any
  int part = -1;             // and of its part
  int moving_object = -1;    // index of the moving planar object hit, if any
  bool dynamic = false;      // a moving thing (character or moving planar object)
  float intensity = 0;       // shaded surface intensity 0..255
};

class WarehouseScene {
 public:
  explicit WarehouseScene(const SceneParams& params);

  /// Poses the characters and moving objects at time t; the queries below are then read-only
  /// (thread-safe).
  void setTime(double t);
  /// The planes a ray from `origin` can hit: those whose front side faces it, in scene order, each
  /// with n·(p0 − origin) (< 0). Computed once per camera position, shared by its rays.
  struct PlanesInView {
    Eigen::Vector3d origin = Eigen::Vector3d::Zero();
    std::vector<std::pair<const ScenePlane*, double>> planes;
    std::vector<std::pair<size_t, uint64_t>> characters;  // those on stage, which of their parts
  };
  PlanesInView planesInView(const Eigen::Vector3d& origin) const;
  /// The part of `view` that rays inside the pyramid of the four directions (in order around it)
  /// can hit: planes and characters entirely outside one of its sides are left out. Casting with
  /// it gives the same hits as with `view` for those rays, at a fraction of the cost.
  PlanesInView cullToPyramid(const PlanesInView& view,
                             const std::array<Eigen::Vector3d, 4>& directions) const;
  /// First surface along origin + t·dir (t > 0). `footprint_per_t`: pixel footprint (m) per unit t,
  /// for texture filtering.
  SceneHit cast(const PlanesInView& view, const Eigen::Vector3d& dir, double footprint_per_t) const;
  SceneHit cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                double footprint_per_t) const {
    return cast(planesInView(origin), dir, footprint_per_t);
  }
  /// Shortest distance from a point to any character's surface at the current time.
  double distanceToCharacters(const Eigen::Vector3d& x) const;

  const std::vector<ScenePlane>& planes() const { return planes_; }
  const ScenePlane* plane(int id) const;
  const std::vector<Character>& characters() const { return characters_; }
  /// Replaces the characters (the paper's ring of dancers) by others.
  void setCharacters(std::vector<Character> characters) { characters_ = std::move(characters); }
  const std::vector<MovingPlanarObject>& movingObjects() const { return moving_; }
  const SceneParams& params() const { return params_; }

 private:
  void addRectangle(int id, const Eigen::Vector3d& centre, const Eigen::Vector3d& normal,
                    const Eigen::Vector3d& u_axis, double width, double height, TextureStyle style);
  void addLightPanels();
  void addPalletTruck(int& next_id, double angle, double phase);
  void addSlidingPanel(int& next_id, double angle, double phase);

  SceneParams params_;
  std::vector<ScenePlane> planes_;
  std::vector<Character> characters_;
  std::vector<MovingPlanarObject> moving_;
};

}  // namespace rpvio::sim
