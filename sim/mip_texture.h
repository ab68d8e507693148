#pragma once
// Procedural, corner-rich textures and their trilinear mip-mapped sampling: the filtering that
// keeps far and grazing surfaces free of aliasing and makes motion sub-pixel consistent.
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

namespace rpvio::sim {

enum class TextureStyle { Wall, Floor, Crate, Shelf };

/// A texture covering `width_m` x `height_m` of a surface at `texel_m` metres per texel, never
/// repeating. Content is a function of (style, seed) only.
cv::Mat makeSurfaceTexture(double width_m, double height_m, double texel_m, TextureStyle style,
                           uint64_t seed);

class MipTexture {
 public:
  MipTexture() = default;
  MipTexture(const cv::Mat& gray8, double texel_m);
  /// Intensity (0..255) at surface coordinates (metres from the texture's origin, clamped to the
  /// texture) for a pixel footprint of `footprint_m` metres on the surface.
  float sample(double u_m, double v_m, double footprint_m) const;

 private:
  float bilinear(int level, double x, double y) const;
  std::vector<cv::Mat> levels_;  // CV_32F, level k has texel size texel_m * 2^k
  double texel_m_ = 1.0;
};

}  // namespace rpvio::sim
