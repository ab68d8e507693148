#pragma once
// Homographies between matched points of a plane (Hartley & Zisserman, 2nd ed., ch. 4): the
// normalized DLT least-squares fit (Alg. 4.2) and a RANSAC over 4-point hypotheses (Alg. 4.6)
// whose best hypothesis can be refined by refitting its inliers (LO-RANSAC). Both work in any
// units; the RANSAC threshold is in the units of `to`.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <vector>

namespace rpvio {

using PointList = std::vector<Eigen::Vector2d>;

/// H with to ~ H from, least squares on the algebraic error of normalized points (≥ 4 matches, not
/// all on a line); nullopt when degenerate.
std::optional<Eigen::Matrix3d> fitHomography(const PointList& from, const PointList& to);

/// The affine map (a homography with last row 0 0 1) with to ≈ A from, least squares (≥ 3 matches,
/// not all on a line); nullopt when degenerate.
std::optional<Eigen::Matrix3d> fitAffine(const PointList& from, const PointList& to);

struct HomographyRansacOptions {
  double threshold = 1.0;    // forward transfer error |H from − to| of an inlier, units of `to`
  double confidence = 0.99;  // that one hypothesis drawn had only inliers
  int max_iterations = 2000;
  // Grow the best hypothesis's inliers by least-squares refits while they find more (LO-RANSAC):
  // an accurate homography, and more inliers near the threshold than a minimal model accepts.
  bool refine = false;
};

/// Inlier flags of the best 4-point hypothesis (most inliers), grown by `refine`. Draws from a
/// fixed seed: the same input gives the same flags. Empty when no non-degenerate sample exists
/// (fewer than 4 matches, or all on a line).
std::vector<bool> homographyRansacInliers(const PointList& from, const PointList& to,
                                          const HomographyRansacOptions& options);

}  // namespace rpvio
