#pragma once
// The local affine image motion around a track from its neighbours' motion (the front-end's
// `local_warps`, used where no plane homography is known).
#include <cstddef>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

namespace rpvio {

/// A track's motion between the previous frame and this one (px).
struct PixelMotion {
  cv::Point2f from, to;
};

/// Neighbourhoods flatter than this (smaller over larger eigenvalue of their offsets' scatter)
/// leave the motion across them unobserved.
constexpr double kMinNeighbourSpreadRatio = 0.1;

/// The local affine map (2x2) of the image motion around `motions[i]`, least squares over its
/// `neighbours` nearest neighbours' displacements relative to its own: it stands for the
/// Jacobian of the surface's homography (the surface is smooth at the scale of the
/// neighbourhood). None with fewer than three neighbours within `reach_px`, or when they lie
/// along a line (spread ratio below kMinNeighbourSpreadRatio).
std::optional<cv::Matx22d> localImageMotion(const std::vector<PixelMotion>& motions, size_t i,
                                            size_t neighbours, double reach_px);

}  // namespace rpvio
