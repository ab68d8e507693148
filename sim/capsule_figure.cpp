#include "sim/capsule_figure.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace rpvio::sim {
namespace {

/// Ray/capsule intersection: infinite cylinder around the segment, clipped, plus the end spheres.
std::optional<double> intersectCapsule(const Capsule& c, const Eigen::Vector3d& o,
                                       const Eigen::Vector3d& d) {
  const Eigen::Vector3d ba = c.b - c.a, oa = o - c.a;
  const double baba = ba.dot(ba), bard = ba.dot(d), baoa = ba.dot(oa);
  const double rdoa = d.dot(oa), oaoa = oa.dot(oa);
  const double a = baba * d.dot(d) - bard * bard;
  const double b = baba * rdoa - baoa * bard;
  const double cc = baba * oaoa - baoa * baoa - c.radius * c.radius * baba;
  const double h = b * b - a * cc;
  if (h < 0) return std::nullopt;
  if (a > 1e-12) {
    const double t = (-b - std::sqrt(h)) / a;
    const double y = baoa + t * bard;
    if (y > 0 && y < baba && t > 0) return t;
  }
  // End caps: spheres at a and b.
  std::optional<double> best;
  for (const Eigen::Vector3d& centre : {c.a, c.b}) {
    const Eigen::Vector3d oc = o - centre;
    const double qa = d.dot(d), qb = oc.dot(d), qc = oc.dot(oc) - c.radius * c.radius;
    const double disc = qb * qb - qa * qc;
    if (disc < 0) continue;
    const double t = (-qb - std::sqrt(disc)) / qa;
    if (t > 0 && (!best || t < *best)) best = t;
  }
  return best;
}

Eigen::Vector3d closestOnSegment(const Capsule& c, const Eigen::Vector3d& x) {
  const Eigen::Vector3d ab = c.b - c.a;
  const double s = std::clamp((x - c.a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return c.a + s * ab;
}

/// Whether o + t·d can meet the sphere (c, r) at some t < t_max (d need not be unit): a cheap
/// test before exact ones; the radius is padded so that rounding never rejects a true hit.
bool sphereReachable(const Eigen::Vector3d& c, double r, const Eigen::Vector3d& o,
                     const Eigen::Vector3d& d, double t_max) {
  const Eigen::Vector3d oc = o - c;
  const double padded = r * (1 + 1e-6) + 1e-9;
  const double qa = d.dot(d), qb = oc.dot(d), qc = oc.dot(oc) - padded * padded;
  const double disc = qb * qb - qa * qc;
  if (disc < 0) return false;
  return (-qb - std::sqrt(disc)) / qa < t_max;  // the entry point comes before t_max
}

double hash01(int a, int b) {
  uint32_t h = static_cast<uint32_t>(a) * 374761393u + static_cast<uint32_t>(b) * 668265263u;
  h = (h ^ (h >> 13)) * 1274126177u;
  return (h ^ (h >> 16)) / 4294967295.0;
}

}  // namespace

void CapsuleFigure::setParts(std::vector<Capsule> parts, const Eigen::Vector3d& bound_centre,
                             double cell_size, int seed) {
  parts_ = std::move(parts);
  bound_centre_ = bound_centre;
  cell_size_ = cell_size;
  seed_ = seed;
  bound_radius_ = 0;
  part_bounds_.clear();
  for (const Capsule& p : parts_)
    part_bounds_.push_back({0.5 * (p.a + p.b), 0.5 * (p.b - p.a).norm() + p.radius});
  for (const Capsule& p : parts_)
    bound_radius_ = std::max({bound_radius_, (p.a - bound_centre_).norm() + p.radius,
                              (p.b - bound_centre_).norm() + p.radius});
}

std::optional<CharacterHit> CapsuleFigure::intersect(const Eigen::Vector3d& o,
                                                     const Eigen::Vector3d& d, double t_max,
                                                     uint64_t parts) const {
  // Bounding spheres first: the figure's, then each part's.
  if (!sphereReachable(bound_centre_, bound_radius_, o, d, t_max)) return std::nullopt;
  int best_part = -1;
  double best_t = t_max;
  for (size_t k = 0; k < parts_.size(); ++k) {
    if (!(parts >> k & 1)) continue;
    if (!sphereReachable(part_bounds_[k].centre, part_bounds_[k].radius, o, d, best_t)) continue;
    const auto t = intersectCapsule(parts_[k], o, d);
    if (t && *t < best_t) best_t = *t, best_part = static_cast<int>(k);
  }
  if (best_part < 0) return std::nullopt;
  const Capsule& part = parts_[best_part];
  CharacterHit hit;
  hit.t = best_t;
  hit.part = best_part;
  hit.point = o + best_t * d;
  const Eigen::Vector3d axis_point = closestOnSegment(part, hit.point);
  hit.normal = (hit.point - axis_point).normalized();
  // Clothes: stripes along the limb and a per-part checker around it (moves with the limb).
  const double along = (axis_point - part.a).norm() / cell_size_;
  const double around = std::atan2(hit.normal.z(), hit.normal.x() + hit.normal.y()) * 3 / M_PI;
  const int cell = static_cast<int>(std::floor(along)) * 31 + static_cast<int>(std::floor(around));
  const double tone = hash01(seed_ * 17 + best_part, cell);
  const double stripe = std::fmod(std::abs(along), 1.0) < 0.3 ? 0.4 : 1.0;
  hit.albedo = static_cast<float>(best_part == 0 ? 150 + 60 * tone : 30 + 200 * tone * stripe);
  return hit;
}

Eigen::Vector3d PartMotion::apply(const Eigen::Vector3d& x) const {
  const double s = std::clamp((x - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  const Eigen::Vector3d radial = x - (a + s * ab);
  return a_then + s * ab_then + turn * radial;
}

std::vector<PartMotion> CapsuleFigure::motionTo(const CapsuleFigure& other) const {
  std::vector<PartMotion> motion;
  for (size_t k = 0; k < parts_.size(); ++k) {
    const Capsule &now = parts_[k], &then = other.parts_[k];
    const Eigen::Vector3d ab = now.b - now.a, ab_then = then.b - then.a;
    motion.push_back({now.a, ab, then.a, ab_then, Eigen::Quaterniond::FromTwoVectors(ab, ab_then)});
  }
  return motion;
}

uint64_t CapsuleFigure::partsInPyramid(const Eigen::Vector3d& origin,
                                       const std::array<Eigen::Vector3d, 4>& side_normals) const {
  uint64_t inside = 0;
  for (size_t k = 0; k < part_bounds_.size(); ++k) {
    const Eigen::Vector3d c = part_bounds_[k].centre - origin;
    const double r = part_bounds_[k].radius * (1 + 1e-6) + 1e-9;
    if (std::none_of(side_normals.begin(), side_normals.end(),
                     [&](const Eigen::Vector3d& n) { return n.dot(c) < -r; }))
      inside |= 1ULL << k;
  }
  return inside;
}

double CapsuleFigure::signedDistance(const Eigen::Vector3d& x) const {
  double best = INFINITY;
  for (const Capsule& p : parts_)
    best = std::min(best, (x - closestOnSegment(p, x)).norm() - p.radius);
  return best;
}

}  // namespace rpvio::sim
