#include "mrpt_modules/frontend/outlier_rejection.h"

#include <Eigen/Core>  // before OpenCV's Eigen header, which needs it
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

#include "mrpt_modules/frontend/homography_ransac.h"

namespace rpvio {
namespace {

std::vector<cv::Point2f> toVirtualCamera(const std::vector<cv::Point2f>& normalized, double f) {
  std::vector<cv::Point2f> out;
  out.reserve(normalized.size());
  for (const auto& p : normalized)
    out.emplace_back(static_cast<float>(f * p.x), static_cast<float>(f * p.y));
  return out;
}

std::vector<bool> toFlags(const std::vector<uchar>& status, size_t n) {
  std::vector<bool> flags(n, false);
  for (size_t i = 0; i < n && i < status.size(); ++i) flags[i] = status[i] != 0;
  return flags;
}

}  // namespace

std::vector<bool> homographyInliers(const std::vector<cv::Point2f>& from,
                                    const std::vector<cv::Point2f>& to, const RansacOptions& opt,
                                    cv::Mat* H) {
  if (from.size() < 4) return std::vector<bool>(from.size(), true);
  PointList a, b;
  for (const auto& p : from) a.push_back(opt.virtual_focal * Eigen::Vector2d(p.x, p.y));
  for (const auto& p : to) b.push_back(opt.virtual_focal * Eigen::Vector2d(p.x, p.y));
  HomographyRansacOptions ransac;
  ransac.threshold = opt.threshold_px;
  ransac.confidence = opt.confidence;
  ransac.refine = opt.refine_homography;
  std::vector<bool> inliers = homographyRansacInliers(a, b, ransac);
  if (inliers.empty()) return std::vector<bool>(from.size(), false);
  if (H) {
    PointList inlier_a, inlier_b;
    for (size_t i = 0; i < inliers.size(); ++i)
      if (inliers[i]) {
        inlier_a.push_back(a[i]);
        inlier_b.push_back(b[i]);
      }
    H->release();
    if (const auto fit = fitHomography(inlier_a, inlier_b)) cv::eigen2cv(*fit, *H);
  }
  return inliers;
}

std::vector<bool> fundamentalInliers(const std::vector<cv::Point2f>& from,
                                     const std::vector<cv::Point2f>& to, const RansacOptions& opt) {
  if (from.size() < 8) return std::vector<bool>(from.size(), true);
  std::vector<uchar> status;
  cv::findFundamentalMat(toVirtualCamera(from, opt.virtual_focal),
                         toVirtualCamera(to, opt.virtual_focal), cv::FM_RANSAC, opt.threshold_px,
                         opt.confidence, status);
  return toFlags(status, from.size());
}

}  // namespace rpvio
