#include "evaluation/plot_canvas.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>

namespace rpvio::eval {
namespace {

constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
const cv::Scalar kAxisColour(60, 60, 60), kGridColour(225, 225, 225);

/// A tick step of 1, 2 or 5 × 10^k giving about `target` intervals over `range`.
double niceStep(double range, int target) {
  const double raw = range / std::max(1, target);
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (raw <= m * magnitude) return m * magnitude;
  return 10 * magnitude;
}

std::string tickText(double v, double step) {
  if (std::abs(v) < 1e-6 * step) v = 0;  // no "-0" from accumulated rounding
  char buf[32];
  std::snprintf(buf, sizeof(buf), step >= 1 ? "%.0f" : step >= 0.1 ? "%.1f" : "%.2f", v);
  return buf;
}

void putCentred(cv::Mat& img, const std::string& text, cv::Point centre, double scale) {
  int base = 0;
  const cv::Size size = cv::getTextSize(text, kFont, scale, 1, &base);
  cv::putText(img, text, centre - cv::Point(size.width / 2, -size.height / 2), kFont, scale,
              kAxisColour, 1, cv::LINE_AA);
}

}  // namespace

cv::Scalar seriesColour(size_t index) {
  static const cv::Scalar kColours[] = {{0, 0, 0},      {178, 114, 0},   {0, 94, 213},
                                        {115, 158, 0},  {167, 121, 204}, {66, 228, 240},
                                        {233, 180, 86}, {0, 159, 230}};
  return kColours[index % (sizeof(kColours) / sizeof(kColours[0]))];
}

void drawPanel(cv::Mat& canvas, const cv::Rect& area, const std::string& title,
               const std::string& x_label, const std::string& y_label,
               const std::vector<PlotSeries>& series, bool equal_aspect) {
  const cv::Rect plot(area.x + 70, area.y + 40, area.width - 90, area.height - 100);
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (const auto& s : series)
    for (const auto& p : s.points) {
      x0 = std::min(x0, p.x()), x1 = std::max(x1, p.x());
      y0 = std::min(y0, p.y()), y1 = std::max(y1, p.y());
    }
  if (!std::isfinite(x0)) x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  const double pad_x = std::max(1e-3, 0.05 * (x1 - x0)), pad_y = std::max(1e-3, 0.05 * (y1 - y0));
  x0 -= pad_x, x1 += pad_x, y0 -= pad_y, y1 += pad_y;
  double sx = plot.width / (x1 - x0), sy = plot.height / (y1 - y0);
  if (equal_aspect) {  // widen the tighter axis so both use the same scale
    const double s = std::min(sx, sy);
    const double cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1);
    x0 = cx - 0.5 * plot.width / s, x1 = cx + 0.5 * plot.width / s;
    y0 = cy - 0.5 * plot.height / s, y1 = cy + 0.5 * plot.height / s;
    sx = sy = s;
  }
  auto toPixel = [&](const Eigen::Vector2d& p) {
    return cv::Point2d(plot.x + (p.x() - x0) * sx, plot.y + plot.height - (p.y() - y0) * sy);
  };

  cv::rectangle(canvas, plot, cv::Scalar(255, 255, 255), cv::FILLED);
  const double step_x = niceStep(x1 - x0, 8), step_y = niceStep(y1 - y0, 6);
  for (double v = std::ceil(x0 / step_x) * step_x; v <= x1; v += step_x) {
    const int px = static_cast<int>(toPixel({v, y0}).x);
    cv::line(canvas, {px, plot.y}, {px, plot.y + plot.height}, kGridColour, 1);
    putCentred(canvas, tickText(v, step_x), {px, plot.y + plot.height + 14}, 0.4);
  }
  for (double v = std::ceil(y0 / step_y) * step_y; v <= y1; v += step_y) {
    const int py = static_cast<int>(toPixel({x0, v}).y);
    cv::line(canvas, {plot.x, py}, {plot.x + plot.width, py}, kGridColour, 1);
    cv::putText(canvas, tickText(v, step_y), {area.x + 8, py + 4}, kFont, 0.4, kAxisColour, 1,
                cv::LINE_AA);
  }
  cv::rectangle(canvas, plot, kAxisColour, 1);
  putCentred(canvas, title, {plot.x + plot.width / 2, area.y + 18}, 0.6);
  putCentred(canvas, x_label, {plot.x + plot.width / 2, plot.y + plot.height + 38}, 0.5);
  cv::putText(canvas, y_label, {area.x + 8, plot.y - 8}, kFont, 0.5, kAxisColour, 1, cv::LINE_AA);

  cv::Mat clip = canvas(plot);
  for (const auto& s : series) {
    std::vector<cv::Point> poly;
    for (const auto& p : s.points) {
      const cv::Point2d q = toPixel(p) - cv::Point2d(plot.x, plot.y);
      poly.emplace_back(static_cast<int>(std::lround(q.x)), static_cast<int>(std::lround(q.y)));
    }
    if (!poly.empty()) cv::polylines(clip, poly, false, s.colour, s.thickness, cv::LINE_AA);
  }
  // Legend, top-left inside the plot.
  int row = 0;
  for (const auto& s : series) {
    if (s.label.empty()) continue;
    const cv::Point at(plot.x + 10, plot.y + 16 + 18 * row++);
    cv::line(canvas, at + cv::Point(0, -4), at + cv::Point(24, -4), s.colour, 3, cv::LINE_AA);
    cv::putText(canvas, s.label, at + cv::Point(30, 0), kFont, 0.45, kAxisColour, 1, cv::LINE_AA);
  }
}

}  // namespace rpvio::eval
