#include "mrpt_modules/initialization/plane_motion_from_homography.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

namespace rpvio {

Eigen::Matrix3d cameraRotationFromBody(const Eigen::Matrix3d& delta_R_body,
                                       const Eigen::Matrix3d& R_BC) {
  // Orientation of camera j in camera i is R_BCᵀ ΔR R_BC; points move by its transpose.
  return (R_BC.transpose() * delta_R_body * R_BC).transpose();
}

std::vector<PlaneMotion> decomposePlaneHomography(const Eigen::Matrix3d& H,
                                                  const std::vector<Eigen::Vector2d>& points_i) {
  cv::Mat H_cv;
  cv::eigen2cv(H, H_cv);
  std::vector<cv::Mat> Rs, ts, ns;
  cv::decomposeHomographyMat(H_cv, cv::Mat::eye(3, 3, CV_64F), Rs, ts, ns);
  std::vector<PlaneMotion> out;
  for (size_t k = 0; k < Rs.size(); ++k) {
    PlaneMotion m;
    cv::cv2eigen(Rs[k], m.R);
    cv::Mat t = ts[k], n = ns[k];
    m.t_over_d = Eigen::Vector3d(t.at<double>(0), t.at<double>(1), t.at<double>(2));
    m.n = Eigen::Vector3d(n.at<double>(0), n.at<double>(1), n.at<double>(2));
    // Points of the plane at positive depth z satisfy n·(z x̄) = d > 0, i.e. n·x̄ > 0.
    bool in_front = true;
    for (const auto& p : points_i) in_front &= m.n.dot(Eigen::Vector3d(p.x(), p.y(), 1)) > 0;
    if (in_front) out.push_back(m);
  }
  return out;
}

std::optional<PlaneMotion> planeMotionFromHomography(const std::vector<Eigen::Vector2d>& points_i,
                                                     const std::vector<Eigen::Vector2d>& points_j,
                                                     const Eigen::Matrix3d& R_gyro,
                                                     const HomographyInitOptions& options,
                                                     std::string* why_not,
                                                     std::vector<PlaneMotion>* candidates_out) {
  auto fail = [&](const std::string& reason) {
    if (why_not) *why_not = reason;
    return std::nullopt;
  };
  if (points_i.size() < options.min_inliers)
    return fail("too few plane features (" + std::to_string(points_i.size()) + ")");
  std::vector<cv::Point2d> a, b;
  for (size_t k = 0; k < points_i.size(); ++k) {
    a.emplace_back(points_i[k].x(), points_i[k].y());
    b.emplace_back(points_j[k].x(), points_j[k].y());
  }
  std::vector<uchar> mask;
  const cv::Mat H_cv = cv::findHomography(
      a, b, cv::RANSAC, options.ransac_threshold_px / options.virtual_focal, mask, 2000, 0.995);
  if (H_cv.empty()) return fail("homography RANSAC failed");
  std::vector<Eigen::Vector2d> inliers_i;
  for (size_t k = 0; k < mask.size(); ++k)
    if (mask[k]) inliers_i.push_back(points_i[k]);
  if (inliers_i.size() < options.min_inliers)
    return fail("too few homography inliers (" + std::to_string(inliers_i.size()) + ")");
  Eigen::Matrix3d H;
  cv::cv2eigen(H_cv, H);
  std::vector<PlaneMotion> candidates = decomposePlaneHomography(H, inliers_i);
  if (candidates.empty()) return fail("no decomposition puts the plane in front of the camera");
  PlaneMotion* best = nullptr;
  for (auto& c : candidates) {
    c.rotation_error_deg = Eigen::AngleAxisd(R_gyro.transpose() * c.R).angle() * 180 / M_PI;
    c.inliers = inliers_i.size();
    if (!best || c.rotation_error_deg < best->rotation_error_deg) best = &c;
  }
  const PlaneMotion chosen = *best;
  if (candidates_out) *candidates_out = candidates;
  return chosen;
}

}  // namespace rpvio
