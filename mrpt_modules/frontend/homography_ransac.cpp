#include "mrpt_modules/frontend/homography_ransac.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <random>

namespace rpvio {
namespace {

const int kMaxRefits = 3;

/// Similarity moving the points' centroid to the origin and their mean distance to it to √2
/// (H&Z §4.4.4); identity scale when all points coincide.
Eigen::Matrix3d normalizingTransform(const PointList& points) {
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const auto& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
  double mean_distance = 0;
  for (const auto& p : points) mean_distance += (p - centroid).norm();
  mean_distance /= static_cast<double>(points.size());
  const double s = mean_distance > 0 ? std::sqrt(2.0) / mean_distance : 1.0;
  Eigen::Matrix3d T;
  T << s, 0, -s * centroid.x(), 0, s, -s * centroid.y(), 0, 0, 1;
  return T;
}

PointList transformed(const Eigen::Matrix3d& T, const PointList& points) {
  PointList out;
  out.reserve(points.size());
  for (const auto& p : points) out.push_back(T(0, 0) * p + T.block<2, 1>(0, 2));
  return out;
}

/// Twice the signed area of the triangle abc.
double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const Eigen::Vector2d u = b - a, v = c - a;
  return u.x() * v.y() - u.y() * v.x();
}

/// A 4-point sample defines a homography of a plane seen from its front when no three of its
/// points are collinear in either image and every triangle keeps its orientation.
bool sampleIsUsable(const std::array<size_t, 4>& s, const PointList& from, const PointList& to) {
  // Normalized coordinates are O(1): a triangle of area below this is a line.
  const double kMinTwiceArea = 1e-8;
  static const int kTriples[4][3] = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
  for (const auto& t : kTriples) {
    const double a = cross(from[s[t[0]]], from[s[t[1]]], from[s[t[2]]]);
    const double b = cross(to[s[t[0]]], to[s[t[1]]], to[s[t[2]]]);
    if (std::abs(a) < kMinTwiceArea || std::abs(b) < kMinTwiceArea || (a > 0) != (b > 0))
      return false;
  }
  return true;
}

/// The homography through four matches with h33 = 1: two rows of the DLT per match (H&Z eq. 4.3)
/// as an 8x8 system.
std::optional<Eigen::Matrix3d> minimalHomography(const std::array<size_t, 4>& s,
                                                 const PointList& from, const PointList& to) {
  Eigen::Matrix<double, 8, 8> A;
  Eigen::Matrix<double, 8, 1> b;
  for (int k = 0; k < 4; ++k) {
    const double x = from[s[k]].x(), y = from[s[k]].y(), u = to[s[k]].x(), v = to[s[k]].y();
    A.row(2 * k) << x, y, 1, 0, 0, 0, -u * x, -u * y;
    A.row(2 * k + 1) << 0, 0, 0, x, y, 1, -v * x, -v * y;
    b(2 * k) = u;
    b(2 * k + 1) = v;
  }
  const Eigen::PartialPivLU<Eigen::Matrix<double, 8, 8>> lu(A);
  if (!(std::abs(lu.determinant()) > 1e-12)) return std::nullopt;
  const Eigen::Matrix<double, 8, 1> h = lu.solve(b);
  Eigen::Matrix3d H;
  H << h(0), h(1), h(2), h(3), h(4), h(5), h(6), h(7), 1;
  return H;
}

/// Inlier flags of H (forward transfer error below `threshold`, point in front) and their count.
size_t classify(const Eigen::Matrix3d& H, const PointList& from, const PointList& to,
                double threshold, std::vector<bool>& flags) {
  const double threshold2 = threshold * threshold;
  size_t count = 0;
  flags.resize(from.size());
  for (size_t i = 0; i < from.size(); ++i) {
    const Eigen::Vector3d q = H * from[i].homogeneous();
    flags[i] = q.z() > 0 && (q.hnormalized() - to[i]).squaredNorm() < threshold2;
    count += flags[i];
  }
  return count;
}

/// Hypotheses needed so that one was all inliers with probability `confidence`, at inlier ratio w
/// (H&Z eq. 4.18).
double requiredIterations(double confidence, double w) {
  const double all_inliers = std::pow(w, 4);
  if (all_inliers >= 1) return 0;
  if (all_inliers <= 0) return INFINITY;
  return std::log(1 - confidence) / std::log(1 - all_inliers);
}

}  // namespace

std::optional<Eigen::Matrix3d> fitHomography(const PointList& from, const PointList& to) {
  if (from.size() < 4 || from.size() != to.size()) return std::nullopt;
  const Eigen::Matrix3d T_from = normalizingTransform(from), T_to = normalizingTransform(to);
  const PointList a = transformed(T_from, from), b = transformed(T_to, to);
  // AᵀA of the DLT rows (H&Z eq. 4.3); its least eigenvector is h.
  Eigen::Matrix<double, 9, 9> AtA = Eigen::Matrix<double, 9, 9>::Zero();
  for (size_t i = 0; i < a.size(); ++i) {
    const double x = a[i].x(), y = a[i].y(), u = b[i].x(), v = b[i].y();
    Eigen::Matrix<double, 9, 1> r1, r2;
    r1 << x, y, 1, 0, 0, 0, -u * x, -u * y, -u;
    r2 << 0, 0, 0, x, y, 1, -v * x, -v * y, -v;
    AtA.selfadjointView<Eigen::Lower>().rankUpdate(r1);
    AtA.selfadjointView<Eigen::Lower>().rankUpdate(r2);
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 9, 9>> eigen(
      AtA.selfadjointView<Eigen::Lower>());
  if (eigen.info() != Eigen::Success) return std::nullopt;
  // A second null direction: the matches do not fix H (points on a line, or coincident).
  const auto& lambda = eigen.eigenvalues();
  if (!(lambda(1) > 1e-12 * lambda(8))) return std::nullopt;
  const Eigen::Matrix<double, 9, 1> h = eigen.eigenvectors().col(0);
  Eigen::Matrix3d Hn;
  Hn << h(0), h(1), h(2), h(3), h(4), h(5), h(6), h(7), h(8);
  Eigen::Matrix3d H = T_to.inverse() * Hn * T_from;
  if (std::abs(H(2, 2)) > 1e-12) H /= H(2, 2);
  return H;
}

std::optional<Eigen::Matrix3d> fitAffine(const PointList& from, const PointList& to) {
  if (from.size() < 3 || from.size() != to.size()) return std::nullopt;
  // Rows [x y 1] of centred points (conditioning); both output coordinates share the system.
  const Eigen::Matrix3d T_from = normalizingTransform(from);
  const PointList a = transformed(T_from, from);
  Eigen::MatrixX3d M(a.size(), 3);
  Eigen::MatrixX2d rhs(a.size(), 2);
  for (size_t i = 0; i < a.size(); ++i) {
    M.row(static_cast<Eigen::Index>(i)) << a[i].x(), a[i].y(), 1;
    rhs.row(static_cast<Eigen::Index>(i)) = to[i].transpose();
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixX3d> qr(M);
  if (qr.rank() < 3) return std::nullopt;
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
  A.topRows<2>() = qr.solve(rhs).transpose();
  return A * T_from;
}

std::vector<bool> homographyRansacInliers(const PointList& from, const PointList& to,
                                          const HomographyRansacOptions& options) {
  const size_t n = from.size();
  if (n < 4 || n != to.size()) return {};
  // Hypotheses in normalized coordinates (well conditioned 8x8 systems); the threshold follows
  // the scale of `to`'s normalization.
  const Eigen::Matrix3d T_from = normalizingTransform(from), T_to = normalizingTransform(to);
  const PointList a = transformed(T_from, from), b = transformed(T_to, to);
  const double threshold = options.threshold * T_to(0, 0);

  std::mt19937 rng(0x5eed);
  std::uniform_int_distribution<size_t> pick(0, n - 1);
  std::vector<bool> best, flags;
  size_t best_count = 0;
  double needed = options.max_iterations;
  for (int iteration = 0; iteration < options.max_iterations && iteration < needed; ++iteration) {
    std::array<size_t, 4> s{};
    for (size_t k = 0; k < 4; ++k) {
      do s[k] = pick(rng);
      while (std::find(s.begin(), s.begin() + static_cast<std::ptrdiff_t>(k), s[k]) !=
             s.begin() + static_cast<std::ptrdiff_t>(k));
    }
    if (!sampleIsUsable(s, a, b)) continue;
    const auto H = minimalHomography(s, a, b);
    if (!H) continue;
    const size_t count = classify(*H, a, b, threshold, flags);
    if (count <= best_count) continue;
    best_count = count;
    best.swap(flags);
    needed = requiredIterations(options.confidence, static_cast<double>(count) / n);
  }
  // Local optimization (Chum et al. 2003), on request: a minimal model carries its four points'
  // noise, so the least-squares fit of its inliers is re-classified while that finds more of them.
  for (int round = 0; options.refine && round < kMaxRefits && best_count >= 4; ++round) {
    PointList inlier_a, inlier_b;
    for (size_t i = 0; i < n; ++i)
      if (best[i]) {
        inlier_a.push_back(a[i]);
        inlier_b.push_back(b[i]);
      }
    const auto H = fitHomography(inlier_a, inlier_b);
    if (!H) break;
    const size_t count = classify(*H, a, b, threshold, flags);
    if (count <= best_count) break;
    best_count = count;
    best.swap(flags);
  }
  return best;
}

}  // namespace rpvio
