#pragma once
// A human-sized articulated figure (head, torso, arms, legs as capsules) dancing in place with a
// repetitive motion: hips sway and bob, torso twists, arms swing overhead, knees bend, and the
// whole figure turns slowly. Non-planar, textured (clothes patterns on the limbs).
#include <Eigen/Core>
#include <array>
#include <optional>

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
};

class DancingCharacter {
 public:
  static constexpr int kParts = 10;  // head, torso, 2 upper arms, 2 forearms, 2 thighs, 2 shins

  /// `base`: position on the floor; `phase` offsets the dance; `height` ~1.8 m.
  DancingCharacter(const Eigen::Vector2d& base, double phase, double height, int seed);

  /// Poses the figure at time t (seconds); the ray queries below use the posed figure.
  void pose(double t);
  std::optional<CharacterHit> intersect(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                                        double t_max) const;
  /// Distance from a world point to the figure's surface (negative inside).
  double signedDistance(const Eigen::Vector3d& x) const;
  /// Where the surface point x of this posed figure is on `other` (the same figure posed at another
  /// time): same part, same place along it, radial offset turned with the part's axis.
  Eigen::Vector3d follow(const Eigen::Vector3d& x, const DancingCharacter& other) const;
  const Eigen::Vector2d& base() const { return base_; }

 private:
  Eigen::Vector2d base_;
  double phase_, scale_;
  int seed_;
  std::array<Capsule, kParts> parts_;
  Eigen::Vector3d bound_centre_;
  double bound_radius_ = 0;
};

}  // namespace rpvio::sim
