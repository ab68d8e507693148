#pragma once
// A figure made of capsules (a person's head, torso and limbs): ray intersection, distance, and a
// clothes pattern that moves with the limbs. The characters of both suites are such figures.
#include <Eigen/Core>
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
};

class CapsuleFigure {
 public:
  /// `parts[0]` is the head (skin tone); `cell_size` (m) is the clothes pattern's cell along a
  /// limb.
  void setParts(std::vector<Capsule> parts, const Eigen::Vector3d& bound_centre, double cell_size,
                int seed);
  std::optional<CharacterHit> intersect(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                                        double t_max) const;
  /// Distance from a world point to the figure's surface (negative inside).
  double signedDistance(const Eigen::Vector3d& x) const;
  /// Where the surface point x of this figure is on `other` (the same figure in another pose): same
  /// part, same place along it, radial offset turned with the part's axis.
  Eigen::Vector3d follow(const Eigen::Vector3d& x, const CapsuleFigure& other) const;
  const std::vector<Capsule>& parts() const { return parts_; }

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
