#pragma once
// Per-plane feature spacing. With one spacing for the whole image, a plane that covers little of
// it (a rack face 30 m away: ~170x40 px) holds ~10 features at 30 px, and the window's estimate
// of its normal is only as good as those (#8). Such a plane gets a tighter spacing, so that it can
// hold a set number of features, and those features are detected before the other planes'.
#include <map>
#include <opencv2/core.hpp>

namespace rpvio {

struct DensePlane {
  double spacing;  // px between this plane's features, below the image's min_distance
  cv::Rect box;    // bounding box of its detectable pixels
};

/// The planes of `mask` (labels 1..254) whose detectable pixels (`detectable` non-zero, CV_8UC1,
/// same size) number fewer than `min_features` · min_distance²: each gets the spacing
/// √(area / min_features), but not below `min_spacing`. None when min_features <= 0.
std::map<int, DensePlane> densePlanes(const cv::Mat& mask, const cv::Mat& detectable,
                                      int min_features, double min_distance, double min_spacing);

}  // namespace rpvio
