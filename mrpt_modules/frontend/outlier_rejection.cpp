#include "mrpt_modules/frontend/outlier_rejection.h"

#include <opencv2/calib3d.hpp>

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
  std::vector<uchar> status;
  const cv::Mat h = cv::findHomography(toVirtualCamera(from, opt.virtual_focal),
                                       toVirtualCamera(to, opt.virtual_focal), cv::RANSAC,
                                       opt.threshold_px, status, 2000, opt.confidence);
  if (H) *H = h;
  if (h.empty()) return std::vector<bool>(from.size(), false);
  return toFlags(status, from.size());
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
