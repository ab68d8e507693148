#include "sim/mip_texture.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <random>

namespace rpvio::sim {
namespace {

/// Multi-octave value noise in [−1, 1]: random grids of growing resolution, cubic upsampling.
cv::Mat valueNoise(cv::Size size, double finest_cell_texels, std::mt19937_64& rng) {
  cv::Mat sum = cv::Mat::zeros(size, CV_32F);
  std::uniform_real_distribution<float> uni(-1.f, 1.f);
  double amplitude = 1.0, cell = finest_cell_texels * 32, total = 0;
  for (int octave = 0; octave < 6 && cell >= finest_cell_texels; ++octave, cell /= 2) {
    const cv::Size grid(std::max(2, static_cast<int>(size.width / cell) + 2),
                        std::max(2, static_cast<int>(size.height / cell) + 2));
    cv::Mat coarse(grid, CV_32F);
    for (int i = 0; i < coarse.rows; ++i)
      for (int j = 0; j < coarse.cols; ++j) coarse.at<float>(i, j) = uni(rng);
    cv::Mat up;
    cv::resize(coarse, up, size, 0, 0, cv::INTER_CUBIC);
    sum += amplitude * up;
    total += amplitude;
    amplitude *= 0.6;
  }
  return sum / total;
}

/// Random filled/outlined rectangles, discs and strokes at several scales: strong corners.
void drawShapes(cv::Mat& img, int count, int min_size, int max_size, std::mt19937_64& rng,
                bool rectangles_only) {
  std::uniform_int_distribution<int> x(0, img.cols - 1), y(0, img.rows - 1);
  std::uniform_int_distribution<int> s(min_size, std::max(min_size, max_size));
  std::uniform_int_distribution<int> grey(15, 240), kind(0, 9);
  for (int k = 0; k < count; ++k) {
    const cv::Point p(x(rng), y(rng));
    const cv::Point q = p + cv::Point(s(rng), s(rng));
    const cv::Scalar c(grey(rng));
    const int what = rectangles_only ? 0 : kind(rng);
    if (what < 5) {
      cv::rectangle(img, p, q, c, what == 0 ? 2 : cv::FILLED, cv::LINE_8);
    } else if (what < 8) {
      cv::circle(img, p, std::max(2, (q.x - p.x) / 2), c, what == 5 ? 2 : cv::FILLED, cv::LINE_8);
    } else {
      cv::line(img, p, q, c, 1 + kind(rng) / 3, cv::LINE_8);
    }
  }
}

}  // namespace

cv::Mat makeSurfaceTexture(double width_m, double height_m, double texel_m, TextureStyle style,
                           uint64_t seed) {
  std::mt19937_64 rng(seed * 7919 + static_cast<uint64_t>(style));
  const cv::Size size(std::max(8, static_cast<int>(std::ceil(width_m / texel_m))),
                      std::max(8, static_cast<int>(std::ceil(height_m / texel_m))));
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  const double base = 90 + 80 * uni(rng), contrast = 40 + 30 * uni(rng);
  cv::Mat noise = valueNoise(size, 4, rng);
  cv::Mat img;
  noise.convertTo(img, CV_8U, contrast, base);
  const double area_m2 = width_m * height_m;
  const int px_per_m = static_cast<int>(1.0 / texel_m);
  switch (style) {
    case TextureStyle::Wall:  // corrugated panels, posters, signs, grime
      for (int x = 0; x < size.width; x += px_per_m * (2 + static_cast<int>(3 * uni(rng))))
        cv::line(img, {x, 0}, {x, size.height}, cv::Scalar(40 + 60 * uni(rng)), 2);
      drawShapes(img, static_cast<int>(area_m2 * 1.5), px_per_m / 5, px_per_m, rng, false);
      drawShapes(img, static_cast<int>(area_m2 * 6), 3, px_per_m / 4, rng, false);
      break;
    case TextureStyle::Floor:  // concrete, painted lanes, stains, debris
      drawShapes(img, static_cast<int>(area_m2 * 0.8), px_per_m / 4, px_per_m, rng, false);
      drawShapes(img, static_cast<int>(area_m2 * 5), 3, px_per_m / 5, rng, false);
      for (int y = 0; y < size.height; y += px_per_m * 4)
        cv::rectangle(img, {0, y}, {size.width, y + px_per_m / 10}, cv::Scalar(225), cv::FILLED);
      break;
    case TextureStyle::Crate:  // cardboard with tape, labels and print
      drawShapes(img, static_cast<int>(area_m2 * 10), px_per_m / 10, px_per_m / 2, rng, true);
      drawShapes(img, static_cast<int>(area_m2 * 30), 2, px_per_m / 8, rng, false);
      cv::rectangle(img, {size.width / 2 - px_per_m / 20, 0},
                    {size.width / 2 + px_per_m / 20, size.height}, cv::Scalar(200), cv::FILLED);
      break;
    case TextureStyle::Shelf:  // racks: beams, uprights and stored goods
      drawShapes(img, static_cast<int>(area_m2 * 8), px_per_m / 6, px_per_m / 2, rng, true);
      drawShapes(img, static_cast<int>(area_m2 * 20), 2, px_per_m / 8, rng, false);
      for (int y = 0; y < size.height; y += px_per_m)
        cv::rectangle(img, {0, y}, {size.width, y + px_per_m / 12}, cv::Scalar(30), cv::FILLED);
      break;
  }
  // Fine speckle: texture at the scale of a few texels everywhere.
  cv::Mat speckle(size, CV_8S);
  cv::RNG speckle_rng(seed);  // seeded: OpenCV's global RNG would differ between scenes
  speckle_rng.fill(speckle, cv::RNG::NORMAL, 0, 10);
  cv::Mat out;
  cv::add(img, speckle, out, cv::noArray(), CV_8U);
  return out;
}

MipTexture::MipTexture(const cv::Mat& gray8, double texel_m) : texel_m_(texel_m) {
  cv::Mat level;
  gray8.convertTo(level, CV_32F);
  levels_.push_back(level);
  while (std::min(level.cols, level.rows) > 4) {
    cv::Mat next;
    cv::pyrDown(level, next);  // Gaussian 5x5 then decimation: a proper low-pass per octave
    levels_.push_back(next);
    level = next;
  }
}

float MipTexture::bilinear(int k, double x, double y) const {
  const cv::Mat& L = levels_[k];
  x = std::clamp(x, 0.0, L.cols - 1.001);
  y = std::clamp(y, 0.0, L.rows - 1.001);
  const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
  const float fx = static_cast<float>(x - x0), fy = static_cast<float>(y - y0);
  const float* r0 = L.ptr<float>(y0);
  const float* r1 = L.ptr<float>(y0 + 1);
  return (1 - fy) * ((1 - fx) * r0[x0] + fx * r0[x0 + 1]) +
         fy * ((1 - fx) * r1[x0] + fx * r1[x0 + 1]);
}

float MipTexture::sample(double u_m, double v_m, double footprint_m) const {
  // Level of detail: log2 of texels per pixel footprint; blend the two nearest levels.
  const double lod = std::clamp(std::log2(std::max(footprint_m / texel_m_, 1e-9)), 0.0,
                                static_cast<double>(levels_.size() - 1));
  const int k0 = static_cast<int>(lod);
  const int k1 = std::min<int>(k0 + 1, static_cast<int>(levels_.size()) - 1);
  const double w = lod - k0;
  // Base texel j is centred at (j + 0.5) texels; cv::pyrDown centres level-k texel i on base
  // texel 2^k i, so the continuous level-k coordinate is (u / texel − 0.5) / 2^k.
  auto at = [&](int k) {
    const double shrink = std::ldexp(1.0, -k);
    return bilinear(k, (u_m / texel_m_ - 0.5) * shrink, (v_m / texel_m_ - 0.5) * shrink);
  };
  return static_cast<float>((1 - w) * at(k0) + w * (k1 == k0 ? at(k0) : at(k1)));
}

}  // namespace rpvio::sim
