#pragma once
// The pixels of a plane mask whose neighbourhood carries only their own plane's label: where the
// tracker detects corners and keeps tracks (a KLT window straddling two surfaces follows a mix of
// their motions).
#include <opencv2/core.hpp>

namespace rpvio {

/// Into `region` (255 / 0): pixels whose neighbourhood (square of side kernel, `iterations` times)
/// carries only their own label, and that label is a plane (not 0, not 255): per-plane erosion in
/// two passes (min == max of the labels). `lowest`, `highest`: buffers for the two passes, kept by
/// the caller.
void uniformPlaneRegion(const cv::Mat& mask, int kernel, int iterations, cv::Mat& lowest,
                        cv::Mat& highest, cv::Mat& region);

}  // namespace rpvio
