#pragma once
// How long each plane is visible in a sequence's plane masks, and which of the planes visible for
// long enough have no entry in a plane map (issue 8: every plane seen for more than 2 s is in the
// map). Two measures per label:
// - seen: the label covers at least minVisiblePlanePixels(klt_window) of the mask;
// - trackable: so many of its pixels have no other label within the tracker's window margin
//   (the pixels where it detects corners and keeps tracks): room for the 10 tracks
//   (kMinPlanePoints) a plane needs to enter the estimator's window, one KLT window apart.
// The margin and the KLT window are the tracker's (`window_margin`, `klt_window` of a mode's
// config): with 10 and 21 px, a face 70 px across is seen (4900 px) but not trackable (50 x 50 px):
// it never holds 10 tracks.
#include <map>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "evaluation/plane_map_accuracy.h"

namespace rpvio::eval {

/// Room for 10 tracks one KLT window apart (px).
constexpr int minVisiblePlanePixels(int klt_window) { return 10 * klt_window * klt_window; }
constexpr double kMinVisibleSeconds = 2.0;  // issue 8: "seen for more than 2 s"

struct LabelVisibility {
  double seen_s = 0;
  double trackable_s = 0;
};

/// Visible time per mask label (1..254) over a sequence of masks.
class PlaneVisibility {
 public:
  /// `min_pixels` of a label make it seen (trackable) in a frame; `window_margin`: the tracker's.
  PlaneVisibility(int min_pixels, int window_margin)
      : min_pixels_(min_pixels), window_margin_(window_margin) {}
  /// A CV_8UC1 label mask stamped t (seconds, after the previous one).
  void addMask(double t, const cv::Mat& mask);
  /// Per label seen in at least one frame: the frames it is seen / trackable in, each counting the
  /// median interval between masks (a missing frame does not count; the first one does).
  std::map<int, LabelVisibility> seconds() const;

 private:
  int min_pixels_, window_margin_;
  std::vector<double> times_;
  std::map<int, size_t> seen_frames_, trackable_frames_;
  cv::Mat lowest_, highest_, trackable_;  // buffers
};

struct MissingPlane {
  int true_id = 0;
  LabelVisibility visible;
};

/// The static true planes without an entry in the evaluated map that were trackable for more than
/// `min_seconds` (`missing`), or only seen for that long (`untrackable`); moving ones are not
/// expected in the map.
struct MissingPlanes {
  std::vector<MissingPlane> missing, untrackable;
};
MissingPlanes missingPlanes(const PlaneMapAccuracy& accuracy, const std::vector<Plane>& truth,
                            const std::map<int, LabelVisibility>& visible,
                            double min_seconds = kMinVisibleSeconds);

}  // namespace rpvio::eval
