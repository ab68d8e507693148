#include "mrpt_modules/loop/loop_verification.h"

#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/features2d.hpp>

namespace rpvio {
namespace {

constexpr double kVirtualFocal = 460;  // px: the unit of loop_ransac_px

LoopCheck rejected(LoopCheck check, std::string why) {
  check.why = std::move(why);
  return check;
}

}  // namespace

LoopCheck verifyLoop(const KeyframeAppearance& query, const KeyframeAppearance& old,
                     const Eigen::Isometry3d& old_body_odometry, const Eigen::Isometry3d& T_BC,
                     const LoopCheckOptions& options) {
  LoopCheck check;
  std::vector<int> with_point;
  for (size_t i = 0; i < query.points.size(); ++i)
    if (query.points[i].world) with_point.push_back(static_cast<int>(i));
  if (with_point.empty() || old.points.empty()) return rejected(check, "no points to match");
  cv::Mat query_descriptors(static_cast<int>(with_point.size()), query.descriptors.cols, CV_8U);
  for (size_t r = 0; r < with_point.size(); ++r)
    query.descriptors.row(with_point[r]).copyTo(query_descriptors.row(static_cast<int>(r)));
  std::vector<std::vector<cv::DMatch>> knn;
  cv::BFMatcher(cv::NORM_HAMMING).knnMatch(query_descriptors, old.descriptors, knn, 2);
  std::vector<cv::Point3d> world;
  std::vector<cv::Point2d> seen;
  std::vector<std::pair<int, int>> planes;  // of each match: the query point's, the old point's
  for (const auto& m : knn) {
    if (m.empty() || m[0].distance > options.loop_max_hamming) continue;
    if (m.size() > 1 && m[0].distance >= options.loop_match_ratio * m[1].distance) continue;
    const Eigen::Vector3d& X = *query.points[with_point[m[0].queryIdx]].world;
    const Eigen::Vector2d& u = old.points[m[0].trainIdx].normalized;
    world.emplace_back(X.x(), X.y(), X.z());
    seen.emplace_back(u.x(), u.y());
    planes.emplace_back(query.points[with_point[m[0].queryIdx]].plane,
                        old.points[m[0].trainIdx].plane);
  }
  check.matches = static_cast<int>(world.size());
  if (check.matches < options.loop_min_inliers)
    return rejected(check, std::to_string(check.matches) + " descriptor matches");
  // The old camera in the query's world: x = π(R X + t) in normalized coordinates (K = I).
  cv::Mat rvec, tvec;
  std::vector<int> inliers;
  const bool solved =
      cv::solvePnPRansac(world, seen, cv::Matx33d::eye(), cv::noArray(), rvec, tvec, false, 100,
                         options.loop_ransac_px / kVirtualFocal, 0.99, inliers);
  check.inliers = static_cast<int>(inliers.size());
  if (!solved || check.inliers < options.loop_min_inliers)
    return rejected(check, std::to_string(check.inliers) + " PnP inliers");
  cv::Matx33d R;
  cv::Rodrigues(rvec, R);
  Eigen::Isometry3d T_cw = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) T_cw.linear()(r, c) = R(r, c);
    T_cw.translation()(r) = tvec.at<double>(r);
  }
  check.old_body = T_cw.inverse() * T_BC.inverse();
  // Both worlds are gravity-aligned: the body's up, seen from the body, must agree.
  const Eigen::Vector3d up_pnp = check.old_body.linear().transpose() * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d up_odometry =
      old_body_odometry.linear().transpose() * Eigen::Vector3d::UnitZ();
  const double tilt_deg = std::acos(std::clamp(up_pnp.dot(up_odometry), -1.0, 1.0)) * 180.0 / M_PI;
  if (tilt_deg > options.loop_max_tilt_deg) {
    char why[64];
    std::snprintf(why, sizeof why, "tilt %.1f deg from the odometry's", tilt_deg);
    return rejected(check, why);
  }
  for (int i : inliers) {
    const auto [query_plane, old_plane] = planes[i];
    if (query_plane == 0 || old_plane == 0) continue;
    ++check.plane_pairs;
    check.same_plane_pairs += query_plane == old_plane;
  }
  if (options.loop_plane_pairs > 0 && check.plane_pairs >= options.loop_plane_pairs &&
      2 * check.same_plane_pairs <= check.plane_pairs)
    return rejected(check, std::to_string(check.plane_pairs - check.same_plane_pairs) + " of " +
                               std::to_string(check.plane_pairs) +
                               " inliers on planes on another plane");
  check.accepted = true;
  return check;
}

}  // namespace rpvio
