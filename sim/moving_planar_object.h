#pragma once
// A rigid set of textured rectangles moving back and forth along a straight path — a pallet truck
// carrying boxes, a sliding panel: surfaces a plane-segmentation network labels as planes although
// they move. The object does not turn: T_WO(t) = translation(p0 + motion.offset(t)), closed form in
// t, so its ground truth is exact at any time.
#include <Eigen/Geometry>
#include <array>
#include <optional>
#include <vector>

#include "common/oscillating_translation.h"
#include "sim/scene_plane.h"

namespace rpvio::sim {

struct MovingFaceHit {
  double t = 0;                                     // ray parameter
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // world
  int id = 0;                                       // the face's plane id
  float intensity = 0;                              // shaded surface intensity 0..255
};

/// A face at some time: world plane n·X = d and its corners (origin, +u, +u+v, +v).
struct PosedFace {
  int id = 0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double distance = 0;
  std::array<Eigen::Vector3d, 4> corners;
};

class MovingPlanarObject {
 public:
  /// `faces` in the object frame, whose axes are the world's; `p0` its origin in the world at
  /// motion offset zero.
  MovingPlanarObject(std::vector<ScenePlane> faces, const Eigen::Vector3d& p0,
                     const OscillatingTranslation& motion);

  Eigen::Isometry3d pose(double t) const;  // T_WO(t)
  /// Poses the object at time t for intersect().
  void setTime(double t);
  /// Nearest front face met by o + t·d with t < t_max (world ray, as posed by setTime).
  std::optional<MovingFaceHit> intersect(const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                                         double t_max, double footprint_per_t) const;
  /// Every face's world plane and corners at time t.
  std::vector<PosedFace> faces(double t) const;
  const OscillatingTranslation& motion() const { return motion_; }

 private:
  std::vector<ScenePlane> faces_;  // object frame
  Eigen::Vector3d p0_, position_;  // world origin at offset zero / at the posed time
  OscillatingTranslation motion_;
  Eigen::Vector3d bound_centre_ = Eigen::Vector3d::Zero();  // object frame
  double bound_radius_ = 0;
};

}  // namespace rpvio::sim
