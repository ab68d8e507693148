#include "sim/mask_degradation.h"

#include <opencv2/imgproc.hpp>
#include <random>
#include <set>

namespace rpvio::sim {

void degradeMask(cv::Mat& mask, const MaskDegradation& opt, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  const cv::Mat characters = mask == 0;
  if (opt.boundary_bleed_px > 0) {
    // Grey dilation of the plane labels (characters are 0, so the max spreads planes over them).
    cv::Mat planes = mask.clone();
    planes.setTo(0, mask == 255);
    cv::Mat grown;
    cv::dilate(planes, grown, cv::Mat(), cv::Point(-1, -1), opt.boundary_bleed_px);
    grown.copyTo(mask, characters);
  }
  if (opt.missed_plane_rate > 0) {
    std::set<int> ids;
    for (int r = 0; r < mask.rows; ++r)
      for (int c = 0; c < mask.cols; ++c) ids.insert(mask.at<uint8_t>(r, c));
    for (int id : ids)
      if (id != 0 && id != 255 && uni(rng) < opt.missed_plane_rate) mask.setTo(0, mask == id);
  }
  if (opt.split_plane_id > 0 && opt.split_plane_id + 100 < 255) {
    cv::Mat right = cv::Mat::zeros(mask.size(), CV_8U);
    right(cv::Rect(mask.cols / 2, 0, mask.cols - mask.cols / 2, mask.rows)).setTo(1);
    mask.setTo(opt.split_plane_id + 100, (mask == opt.split_plane_id) & right);
  }
  if (opt.spurious_blob_rate > 0 && uni(rng) < opt.spurious_blob_rate) {
    std::vector<cv::Point> on_character;
    cv::findNonZero(characters, on_character);
    if (!on_character.empty()) {
      const cv::Point at =
          on_character[static_cast<size_t>(uni(rng) * on_character.size()) % on_character.size()];
      cv::ellipse(mask, at,
                  cv::Size(4 + static_cast<int>(8 * uni(rng)), 4 + static_cast<int>(8 * uni(rng))),
                  180 * uni(rng), 0, 360, cv::Scalar(1 + static_cast<int>(9 * uni(rng))),
                  cv::FILLED);
    }
  }
}

}  // namespace rpvio::sim
