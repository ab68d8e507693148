#include "mrpt_modules/initialization/essential_two_view.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

namespace rpvio {

std::optional<RelativePose> relativePoseFromEssential(const std::vector<Eigen::Vector2d>& u_i,
                                                      const std::vector<Eigen::Vector2d>& u_j,
                                                      const EssentialOptions& options,
                                                      std::string* why_not) {
  auto fail = [&](const std::string& reason) {
    if (why_not) *why_not = reason;
    return std::nullopt;
  };
  if (u_i.size() < options.min_inliers || u_i.size() != u_j.size())
    return fail("too few correspondences (" + std::to_string(u_i.size()) + ")");
  std::vector<cv::Point2d> a, b;
  for (size_t k = 0; k < u_i.size(); ++k) {
    a.emplace_back(u_i[k].x(), u_i[k].y());
    b.emplace_back(u_j[k].x(), u_j[k].y());
  }
  cv::Mat mask;
  const cv::Mat E = cv::findEssentialMat(a, b, cv::Mat::eye(3, 3, CV_64F), cv::RANSAC, 0.999,
                                         options.ransac_threshold_px / options.virtual_focal, mask);
  if (E.rows != 3 || E.cols != 3) return fail("essential matrix RANSAC failed");
  // recoverPose: x_j = R x_i + t (unit t), counting the points in front of both cameras.
  cv::Mat R_cv, t_cv;
  const int in_front = cv::recoverPose(E, a, b, cv::Mat::eye(3, 3, CV_64F), R_cv, t_cv, 1e6, mask);
  if (in_front < static_cast<int>(options.min_inliers))
    return fail("too few essential-matrix inliers in front of the cameras (" +
                std::to_string(in_front) + ")");
  Eigen::Matrix3d R_j_i;
  Eigen::Vector3d t_j_i;
  cv::cv2eigen(R_cv, R_j_i);
  cv::cv2eigen(t_cv, t_j_i);
  RelativePose out;
  out.i_j = CameraPose{R_j_i.transpose(), -R_j_i.transpose() * t_j_i};
  for (int k = 0; k < mask.rows; ++k) out.inlier.push_back(mask.at<uchar>(k) != 0);
  out.inliers = static_cast<size_t>(in_front);
  return out;
}

}  // namespace rpvio
