#pragma once
// Drift-free sub-pixel alignment of a feature on the image it was born in. The birth patch is
// warped by the local affine map predicted by the feature's plane (product of the frame-to-frame
// plane homographies' Jacobians), so perspective and scale change along the track do not bias the
// match as they bias a translational KLT. Solved for translation, contrast gain and offset
// (Gauss–Newton, 4 parameters).
#include <opencv2/core.hpp>
#include <optional>

namespace rpvio {

struct TemplateAlignmentOptions {
  int half_window = 10;  // patch of (2 half_window + 1)² pixels of the current image
  int max_iterations = 10;
  double converged_px = 0.003;   // stop when the translation step is this small
  double min_gain = 0.5;         // contrast gain accepted in [min_gain, 1 / min_gain]
  double min_correlation = 0.9;  // zero-mean NCC of the aligned patch with the warped template
};

/// Position in `image` (CV_8UC1) of the point born at `birth_pixel` in `birth_image`, starting
/// from `initial`. `warp` maps offsets around the birth pixel to offsets in `image`
/// (invertible). Empty when a patch leaves an image, the system is singular, it diverges (more
/// than one window half-width from `initial`), the contrast gain is implausible or the aligned
/// patch does not correlate with the warped template.
std::optional<cv::Point2f> alignWarpedTemplate(const cv::Mat& birth_image, cv::Point2f birth_pixel,
                                               const cv::Matx22d& warp, const cv::Mat& image,
                                               cv::Point2f initial,
                                               const TemplateAlignmentOptions& options = {});

/// Jacobian of the homography x ↦ π(H x̃) at `x` (pixels to pixels).
cv::Matx22d homographyJacobian(const cv::Matx33d& H, cv::Point2f x);

}  // namespace rpvio
