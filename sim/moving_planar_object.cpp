#include "sim/moving_planar_object.h"

#include <algorithm>
#include <cmath>

namespace rpvio::sim {
namespace {

std::array<Eigen::Vector3d, 4> cornersOf(const ScenePlane& f) {
  const Eigen::Vector3d u = f.width * f.u_axis, v = f.height * f.v_axis;
  return {f.origin, f.origin + u, f.origin + u + v, f.origin + v};
}

}  // namespace

MovingPlanarObject::MovingPlanarObject(std::vector<ScenePlane> faces, const Eigen::Vector3d& p0,
                                       const OscillatingTranslation& motion)
    : faces_(std::move(faces)), p0_(p0), motion_(motion) {
  std::vector<Eigen::Vector3d> corners;
  for (const ScenePlane& f : faces_)
    for (const Eigen::Vector3d& c : cornersOf(f)) corners.push_back(c);
  for (const Eigen::Vector3d& c : corners) bound_centre_ += c / static_cast<double>(corners.size());
  for (const Eigen::Vector3d& c : corners)
    bound_radius_ = std::max(bound_radius_, (c - bound_centre_).norm());
  setTime(0);
}

Eigen::Isometry3d MovingPlanarObject::pose(double t) const {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = p0_ + motion_.offset(t);
  return T;
}

void MovingPlanarObject::setTime(double t) { position_ = pose(t).translation(); }

std::optional<MovingFaceHit> MovingPlanarObject::intersect(const Eigen::Vector3d& o,
                                                           const Eigen::Vector3d& d, double t_max,
                                                           double footprint_per_t) const {
  const Eigen::Vector3d o_obj = o - position_;  // T_OW o: the object does not turn
  // Bounding sphere first (d need not be unit): no real root of |o + t d − c|² = r², or both
  // roots behind the origin or beyond t_max.
  const Eigen::Vector3d oc = o_obj - bound_centre_;
  const double qa = d.dot(d), qb = oc.dot(d), qc = oc.dot(oc) - bound_radius_ * bound_radius_;
  const double disc = qb * qb - qa * qc;
  if (disc < 0) return std::nullopt;
  const double far = (-qb + std::sqrt(disc)) / qa, near = (-qb - std::sqrt(disc)) / qa;
  if (far <= 0 || near >= t_max) return std::nullopt;
  const ScenePlane* best = nullptr;
  double best_t = t_max, best_u = 0, best_v = 0;
  for (const ScenePlane& f : faces_) {
    double t, u, v;
    if (f.intersectFront(o_obj, d, f.normal.dot(f.origin - o_obj), best_t, t, u, v))
      best = &f, best_t = t, best_u = u, best_v = v;
  }
  if (!best) return std::nullopt;
  MovingFaceHit hit;
  hit.t = best_t;
  hit.point = o + best_t * d;
  hit.id = best->id;
  hit.intensity = best->shadeAt(best_u, best_v, d, best_t, footprint_per_t);
  return hit;
}

std::vector<PosedFace> MovingPlanarObject::faces(double t) const {
  const Eigen::Vector3d p = pose(t).translation();
  std::vector<PosedFace> out;
  for (const ScenePlane& f : faces_) {
    PosedFace posed;
    posed.id = f.id;
    posed.normal = f.normal;
    posed.corners = cornersOf(f);
    for (Eigen::Vector3d& c : posed.corners) c += p;
    posed.distance = f.normal.dot(posed.corners[0]);  // n·X = d
    out.push_back(posed);
  }
  return out;
}

}  // namespace rpvio::sim
