#pragma once
// Makes ground-truth plane masks look like a segmentation CNN's output, so robustness to imperfect
// masks can be measured. All off by default; deterministic for a given seed.
#include <cstdint>
#include <opencv2/core.hpp>

#include "common/options.h"

namespace rpvio::sim {

struct MaskDegradation {
  int boundary_bleed_px = 0;       // plane labels bleed this many pixels onto characters
  double missed_plane_rate = 0.0;  // per frame and plane: probability the plane is labelled 0
  int split_plane_id = 0;          // this plane's right half gets id split_plane_id + 100
  double spurious_blob_rate =
      0.0;  // per frame: probability of a plane-labelled blob on a character
  template <class Visitor>
  void fields(Visitor& v) {
    RPVIO_OPTION(v, boundary_bleed_px);
    RPVIO_OPTION(v, missed_plane_rate);
    RPVIO_OPTION(v, split_plane_id);
    RPVIO_OPTION(v, spurious_blob_rate);
  }
  bool enabled() const {
    return boundary_bleed_px > 0 || missed_plane_rate > 0 || split_plane_id > 0 ||
           spurious_blob_rate > 0;
  }
};

/// Degrades `mask` in place (labels: 0 character, 1..254 planes, 255 nothing).
void degradeMask(cv::Mat& mask, const MaskDegradation& options, uint64_t seed);

}  // namespace rpvio::sim
