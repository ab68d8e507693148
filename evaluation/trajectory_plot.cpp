#include "evaluation/trajectory_plot.h"

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "common/atomic_file.h"
#include "evaluation/plot_canvas.h"

namespace rpvio::eval {
namespace {

/// Projects positions on two axes; a gap longer than 1 s (lost track) starts a new polyline.
std::vector<PlotSeries> viewOf(const Trajectory& traj, int a, int b, const std::string& label,
                               cv::Scalar colour, int thickness) {
  std::vector<PlotSeries> parts(1, PlotSeries{label, {}, colour, thickness});
  for (size_t i = 0; i < traj.size(); ++i) {
    if (i > 0 && traj[i].t - traj[i - 1].t > 1.0) parts.push_back({"", {}, colour, thickness});
    parts.back().points.emplace_back(traj[i].p[a], traj[i].p[b]);
  }
  return parts;
}

}  // namespace

void writeTrajectoryPlot(const std::string& png_path, const Trajectory& gt,
                         const std::vector<PlottedEstimate>& estimates, const std::string& title) {
  const int width = 1500, height = 1150;
  cv::Mat canvas(height, width, CV_8UC3, cv::Scalar(245, 245, 245));
  std::vector<PlotSeries> top, side, error;
  const auto append = [](std::vector<PlotSeries>& dst, std::vector<PlotSeries> src) {
    dst.insert(dst.end(), src.begin(), src.end());
  };
  append(top, viewOf(gt, 0, 1, "ground truth", seriesColour(0), 3));
  append(side, viewOf(gt, 0, 2, "ground truth", seriesColour(0), 3));
  for (size_t k = 0; k < estimates.size(); ++k) {
    const auto& e = estimates[k];
    char label[160];
    std::snprintf(label, sizeof(label), "%s (ATE %.3f m)", e.label.c_str(), e.result->ate.rmse);
    append(top, viewOf(e.result->aligned_estimate, 0, 1, label, seriesColour(k + 1), 2));
    append(side, viewOf(e.result->aligned_estimate, 0, 2, label, seriesColour(k + 1), 2));
    PlotSeries err{e.label, {}, seriesColour(k + 1), 2};
    const double t0 = gt.empty() ? 0 : gt.front().t;
    for (size_t i = 0; i < e.result->times.size(); ++i)
      err.points.emplace_back(e.result->times[i] - t0, e.result->errors[i]);
    error.push_back(err);
  }
  cv::putText(canvas, title, {20, 30}, cv::FONT_HERSHEY_SIMPLEX, 0.8, cv::Scalar(0, 0, 0), 2,
              cv::LINE_AA);
  drawPanel(canvas, {0, 45, width / 2, 700}, "top view", "x [m]", "y [m]", top, true);
  drawPanel(canvas, {width / 2, 45, width / 2, 700}, "side view", "x [m]", "z [m]", side, true);
  drawPanel(canvas, {0, 760, width, 390}, "translation error after alignment",
            "time since start of ground truth [s]", "ATE [m]", error, false);
  const std::string tmp = temporaryPathFor(png_path) + ".png";
  if (!cv::imwrite(tmp, canvas)) throw std::runtime_error(png_path + ": cannot write plot");
  std::filesystem::rename(tmp, png_path);
}

}  // namespace rpvio::eval
