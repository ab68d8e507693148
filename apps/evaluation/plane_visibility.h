#pragma once
// How long each plane is visible in a sequence's plane masks, and which of the planes visible for
// long enough have no entry in a plane map (issue 8: every plane seen for more than 2 s is in the
// map). Visible means covering at least kMinVisiblePlanePixels in a mask: room for the 10 tracks
// (kMinPlanePoints) a plane needs to enter the estimator's window, one KLT window (21 px) apart.
#include <map>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "apps/evaluation/plane_map_accuracy.h"

namespace rpvio::eval {

constexpr int kMinVisiblePlanePixels = 10 * 21 * 21;
constexpr double kMinVisibleSeconds = 2.0;  // issue 8: "seen for more than 2 s"

/// Visible time per mask label (1..254) over a sequence of masks.
class PlaneVisibility {
 public:
  explicit PlaneVisibility(int min_pixels = kMinVisiblePlanePixels) : min_pixels_(min_pixels) {}
  /// A CV_8UC1 label mask stamped t (seconds, after the previous one).
  void addMask(double t, const cv::Mat& mask);
  /// Seconds per label: the frames it is visible in, each counting the median interval between
  /// masks (a missing frame does not count; the first one does).
  std::map<int, double> seconds() const;

 private:
  int min_pixels_;
  std::vector<double> times_;
  std::map<int, size_t> frames_;  // label → frames visible
};

/// Every PLANE_MASK of `rawlog` (InputError naming the file and entry on bad input).
std::map<int, double> planeVisibleSeconds(const std::string& rawlog,
                                          int min_pixels = kMinVisiblePlanePixels);

struct MissingPlane {
  int true_id = 0;
  double visible_s = 0;
};

/// The true planes visible for more than `min_seconds` without an entry in the evaluated map.
std::vector<MissingPlane> missingPlanes(const PlaneMapAccuracy& accuracy,
                                        const std::vector<Plane>& truth,
                                        const std::map<int, double>& visible_s,
                                        double min_seconds = kMinVisibleSeconds);

}  // namespace rpvio::eval
