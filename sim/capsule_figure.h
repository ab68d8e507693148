#pragma once
// A figure made of capsules (a person's head, torso and limbs): ray intersection, distance, and a
// clothes pattern that moves with the limbs. The characters of both suites are such figures.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

namespace rpvio::sim {

struct Capsule {
  Eigen::Vector3d a, b;  // segment end points (world)
  double radius;
};

struct CharacterHit {
  double t;               // ray parameter
  Eigen::Vector3d point;  // world
  Eigen::Vector3d normal;
  float albedo;  // 0..255 intensity of the clothes/skin pattern at the point
  int part;      // index of the capsule hit
};

/// How one part moves between two poses of a figure: a surface point keeps its place along the
/// part, and its radial offset turns with the part's axis.
struct PartMotion {
  Eigen::Vector3d a, ab;            // the part's axis in the first pose
  Eigen::Vector3d a_then, ab_then;  // and in the other
  Eigen::Quaterniond turn;          // ab → ab_then (shortest arc)
  /// Where the surface point x of the first pose is in the other.
  Eigen::Vector3d apply(const Eigen::Vector3d& x) const;
};

class CapsuleFigure {
 public:
  /// `parts[0]` is the head (skin tone); `cell_size` (m) is the clothes pattern's cell along a
  /// limb.
  void setParts(std::vector<Capsule> parts, const Eigen::Vector3d& bound_centre, double cell_size,
                int seed);
  /// `parts`: bit k set = part k may be hit (a tile's culling, partsInPyramid); all by default.
  std::optional<CharacterHit> intersect(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                                        double t_max, uint64_t parts = ~0ULL) const;
  /// Bit k set unless part k lies entirely outside one of the pyramid's sides (inward unit
  /// normals through `origin`).
  uint64_t partsInPyramid(const Eigen::Vector3d& origin,
                          const std::array<Eigen::Vector3d, 4>& side_normals) const;
  /// Distance from a world point to the figure's surface (negative inside).
  double signedDistance(const Eigen::Vector3d& x) const;
  /// How each part moves from this pose to `other` (the same figure in another pose).
  std::vector<PartMotion> motionTo(const CapsuleFigure& other) const;
  const std::vector<Capsule>& parts() const { return parts_; }
  /// A sphere around the whole figure.
  const Eigen::Vector3d& boundCentre() const { return bound_centre_; }
  double boundRadius() const { return bound_radius_; }

 private:
  std::vector<Capsule> parts_;
  struct Sphere {
    Eigen::Vector3d centre;
    double radius;
  };
  std::vector<Sphere> part_bounds_;  // around each part: cheap rejection before the capsule
  Eigen::Vector3d bound_centre_ = Eigen::Vector3d::Zero();
  double bound_radius_ = 0, cell_size_ = 0.06;
  int seed_ = 0;
};

}  // namespace rpvio::sim
