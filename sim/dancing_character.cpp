#include "sim/dancing_character.h"

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

double hash01(int a, int b) {
  uint32_t h = static_cast<uint32_t>(a) * 374761393u + static_cast<uint32_t>(b) * 668265263u;
  h = (h ^ (h >> 13)) * 1274126177u;
  return (h ^ (h >> 16)) / 4294967295.0;
}

}  // namespace

DancingCharacter::DancingCharacter(const Eigen::Vector2d& base, double phase, double height,
                                   int seed)
    : base_(base), phase_(phase), scale_(height / 1.8), seed_(seed) {
  pose(0.0);
}

void DancingCharacter::pose(double t) {
  const double w = 2 * M_PI / 1.6, s = scale_;  // one dance cycle every 1.6 s
  const double c = w * t + phase_;
  const double heading = 0.35 * t + phase_;       // slow turn in place
  const double sway = 0.12 * s * std::sin(c);     // hips left-right
  const double bob = 0.06 * s * std::sin(2 * c);  // up-down, twice per cycle
  const double twist = 0.35 * std::sin(c);        // torso twist
  const Eigen::Matrix3d R_heading =
      Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Matrix3d R_torso =
      R_heading * Eigen::AngleAxisd(twist, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
      Eigen::AngleAxisd(0.15 * std::sin(c), Eigen::Vector3d::UnitX()).toRotationMatrix();
  const Eigen::Vector3d root(base_.x(), base_.y(), 0);
  auto local = [&](const Eigen::Matrix3d& R, double x, double y, double z) {
    return Eigen::Vector3d(R * Eigen::Vector3d(x, y, z));
  };
  const Eigen::Vector3d hip = root + local(R_heading, 0, sway, (0.95 * s) - 0.05 * s + bob);
  const Eigen::Vector3d neck = hip + local(R_torso, 0, 0, 0.5 * s);
  const Eigen::Vector3d head = neck + local(R_torso, 0, 0, 0.2 * s);
  parts_[0] = {head, head + local(R_torso, 0, 0, 0.02 * s), 0.11 * s};
  parts_[1] = {hip + local(R_torso, 0, 0, 0.12 * s), neck - local(R_torso, 0, 0, 0.05 * s),
               0.16 * s};
  for (int side = 0; side < 2; ++side) {
    const double sg = side == 0 ? 1.0 : -1.0;
    // Arms: swing up overhead and down, in opposition.
    const double lift = 1.2 + 1.1 * std::sin(c + side * M_PI);
    const Eigen::Vector3d shoulder = neck + local(R_torso, 0, sg * 0.2 * s, -0.04 * s);
    const Eigen::Vector3d elbow =
        shoulder + local(R_torso, 0.1 * s * std::cos(c), sg * 0.29 * s * std::sin(lift),
                         -0.29 * s * std::cos(lift));
    const double bend = 0.6 + 0.5 * std::sin(2 * c + side);
    const Eigen::Vector3d hand =
        elbow + local(R_torso, 0.15 * s * std::sin(bend), sg * 0.2 * s * std::sin(lift + bend),
                      -0.26 * s * std::cos(lift + bend));
    parts_[2 + side] = {shoulder, elbow, 0.055 * s};
    parts_[4 + side] = {elbow, hand, 0.048 * s};
    // Legs: knees bend with the bob, feet stay planted apart.
    const Eigen::Vector3d hip_joint = hip + local(R_heading, 0, sg * 0.1 * s, 0);
    const Eigen::Vector3d foot = root + local(R_heading, 0, sg * 0.18 * s, 0.06 * s);
    const Eigen::Vector3d mid = 0.5 * (hip_joint + foot);
    const double leg = 0.47 * s, half = 0.5 * (hip_joint - foot).norm();
    const double out = std::sqrt(std::max(0.0, leg * leg - half * half));
    const Eigen::Vector3d knee = mid + local(R_heading, out, sg * 0.03 * s, 0);
    parts_[6 + side] = {hip_joint, knee, 0.075 * s};
    parts_[8 + side] = {knee, foot, 0.06 * s};
  }
  bound_centre_ = root + Eigen::Vector3d(0, 0, 1.0 * s);
  bound_radius_ = 0;
  for (const Capsule& p : parts_)
    bound_radius_ = std::max({bound_radius_, (p.a - bound_centre_).norm() + p.radius,
                              (p.b - bound_centre_).norm() + p.radius});
}

std::optional<CharacterHit> DancingCharacter::intersect(const Eigen::Vector3d& o,
                                                        const Eigen::Vector3d& d,
                                                        double t_max) const {
  // Bounding sphere first (d need not be unit).
  const Eigen::Vector3d oc = o - bound_centre_;
  const double qa = d.dot(d), qb = oc.dot(d), qc = oc.dot(oc) - bound_radius_ * bound_radius_;
  if (qb * qb - qa * qc < 0) return std::nullopt;
  int best_part = -1;
  double best_t = t_max;
  for (int k = 0; k < kParts; ++k) {
    const auto t = intersectCapsule(parts_[k], o, d);
    if (t && *t < best_t) best_t = *t, best_part = k;
  }
  if (best_part < 0) return std::nullopt;
  const Capsule& part = parts_[best_part];
  CharacterHit hit;
  hit.t = best_t;
  hit.point = o + best_t * d;
  const Eigen::Vector3d axis_point = closestOnSegment(part, hit.point);
  hit.normal = (hit.point - axis_point).normalized();
  // Clothes: stripes along the limb and a per-part checker around it (moves with the limb).
  const double along = (axis_point - part.a).norm() / (0.06 * scale_);
  const double around = std::atan2(hit.normal.z(), hit.normal.x() + hit.normal.y()) * 3 / M_PI;
  const int cell = static_cast<int>(std::floor(along)) * 31 + static_cast<int>(std::floor(around));
  const double tone = hash01(seed_ * 17 + best_part, cell);
  const double stripe = std::fmod(std::abs(along), 1.0) < 0.3 ? 0.4 : 1.0;
  hit.albedo = static_cast<float>(best_part == 0 ? 150 + 60 * tone : 30 + 200 * tone * stripe);
  return hit;
}

double DancingCharacter::signedDistance(const Eigen::Vector3d& x) const {
  double best = INFINITY;
  for (const Capsule& p : parts_)
    best = std::min(best, (x - closestOnSegment(p, x)).norm() - p.radius);
  return best;
}

Eigen::Vector3d DancingCharacter::follow(const Eigen::Vector3d& x,
                                         const DancingCharacter& other) const {
  int part = 0;
  double best = INFINITY;
  for (int k = 0; k < kParts; ++k) {
    const double off = std::abs((x - closestOnSegment(parts_[k], x)).norm() - parts_[k].radius);
    if (off < best) best = off, part = k;
  }
  const Capsule &now = parts_[part], &then = other.parts_[part];
  const Eigen::Vector3d ab = now.b - now.a, ab_then = then.b - then.a;
  const double s = std::clamp((x - now.a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  const Eigen::Vector3d radial = x - (now.a + s * ab);
  return then.a + s * ab_then + Eigen::Quaterniond::FromTwoVectors(ab, ab_then) * radial;
}

}  // namespace rpvio::sim
