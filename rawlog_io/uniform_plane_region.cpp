#include "rawlog_io/uniform_plane_region.h"

#include <cstdint>
#include <opencv2/imgproc.hpp>

namespace rpvio {

void uniformPlaneRegion(const cv::Mat& mask, int kernel, int iterations, cv::Mat& lowest,
                        cv::Mat& highest, cv::Mat& region) {
  const bool eroded = iterations > 0 && kernel > 1;
  if (eroded) {
    const cv::Mat k = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(kernel, kernel));
    cv::erode(mask, lowest, k, cv::Point(-1, -1), iterations, cv::BORDER_REPLICATE);
    cv::dilate(mask, highest, k, cv::Point(-1, -1), iterations, cv::BORDER_REPLICATE);
  }
  region.create(mask.size(), CV_8U);
  const int cols = mask.cols;
  for (int y = 0; y < mask.rows; ++y) {
    const uint8_t* label = mask.ptr<uint8_t>(y);
    const uint8_t* lo = eroded ? lowest.ptr<uint8_t>(y) : label;
    const uint8_t* hi = eroded ? highest.ptr<uint8_t>(y) : label;
    uint8_t* out = region.ptr<uint8_t>(y);
    // Non-short-circuit tests and a loop bound in a local: the loop vectorizes.
    for (int x = 0; x < cols; ++x)
      out[x] = ((lo[x] == hi[x]) & (label[x] != 0) & (label[x] != 255)) ? 255 : 0;
  }
}

}  // namespace rpvio
