#pragma once
// A plot panel drawn with OpenCV: data→pixel mapping with "nice" metre ticks, axes, labels,
// polylines and a legend. Small enough to need no plotting dependency.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace rpvio::eval {

struct PlotSeries {
  std::string label;
  std::vector<Eigen::Vector2d> points;
  cv::Scalar colour;
  int thickness = 2;
};

/// Draws `series` in the rectangle `area` of `canvas`. With `equal_aspect`, one metre is the same
/// number of pixels on both axes (trajectory views).
void drawPanel(cv::Mat& canvas, const cv::Rect& area, const std::string& title,
               const std::string& x_label, const std::string& y_label,
               const std::vector<PlotSeries>& series, bool equal_aspect);

/// Distinct, colour-blind-friendly colours (BGR); index 0 is black for the ground truth.
cv::Scalar seriesColour(size_t index);

}  // namespace rpvio::eval
