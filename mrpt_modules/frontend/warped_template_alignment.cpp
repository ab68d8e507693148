#include "mrpt_modules/frontend/warped_template_alignment.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "mrpt_modules/frontend/simd_clones.h"

namespace rpvio {
namespace {

// Sums over a patch run in kLanes interleaved partial sums (a GCC/Clang vector extension), added
// lane by lane in a fixed order at the end: the loops vectorize without reordering any sum, so the
// result does not depend on the instruction set the lanes are mapped to.
constexpr int kLanes = 8;
using Lanes = float __attribute__((vector_size(kLanes * sizeof(float))));

/// kLanes floats from p (no alignment needed).
inline Lanes load(const float* p) {
  Lanes v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

double total(Lanes v) {
  double sum = 0;
  for (int l = 0; l < kLanes; ++l) sum += v[l];
  return sum;
}

bool inside(const cv::Mat& image, double x, double y) {
  return x >= 0 && y >= 0 && x < image.cols - 1 && y < image.rows - 1;
}

/// Bilinear samples of a CV_8UC1 image at p + k·step, k = 0..count−1, into `out`; the caller
/// keeps every point inside [0, cols−1) × [0, rows−1).
void sampleLine(const cv::Mat& image, cv::Vec2d p, cv::Vec2d step, int count, float* out) {
  const uint8_t* data = image.data;
  const size_t stride = image.step[0];
  for (int k = 0; k < count; ++k) {
    const double x = p[0] + k * step[0], y = p[1] + k * step[1];
    const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
    const float ax = static_cast<float>(x - x0), ay = static_cast<float>(y - y0);
    const uint8_t* row0 = data + y0 * stride + x0;
    const uint8_t* row1 = row0 + stride;
    const float top = row0[0] + ax * (row0[1] - row0[0]);
    const float bottom = row1[0] + ax * (row1[1] - row1[0]);
    out[k] = top + ay * (bottom - top);
  }
}

/// The side x side image samples I(x + i, y + j), i, j = 0..side−1, into `out` (row by row);
/// every sample shares the fractional part of (x, y): one set of bilinear weights. The caller
/// keeps the patch inside.
RPVIO_AVX2_CLONES void samplePatch(const cv::Mat& image, double x, double y, int side, float* out) {
  const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
  const float ax = static_cast<float>(x - x0), ay = static_cast<float>(y - y0);
  const float w00 = (1 - ax) * (1 - ay), w01 = ax * (1 - ay), w10 = (1 - ax) * ay, w11 = ax * ay;
  for (int j = 0; j < side; ++j) {
    const uint8_t* row0 = image.ptr<uint8_t>(y0 + j) + x0;
    const uint8_t* row1 = image.ptr<uint8_t>(y0 + j + 1) + x0;
    float* I = out + static_cast<size_t>(j) * side;
    for (int i = 0; i < side; ++i)
      I[i] = w00 * row0[i] + w01 * row0[i + 1] + w10 * row1[i] + w11 * row1[i + 1];
  }
}

/// Zero-mean normalized cross-correlation of T and I over `padded` samples (a multiple of
/// kLanes), the padding zero in both, n of them real; about their means (no cancellation in
/// float).
double zeroMeanCorrelation(const float* T, const float* I, const float* real, int n, int padded) {
  Lanes st{}, si{};
  for (int k = 0; k < padded; k += kLanes) st += load(T + k), si += load(I + k);
  const float mt = static_cast<float>(total(st) / n), mi = static_cast<float>(total(si) / n);
  Lanes tt{}, ii{}, ti{};
  for (int k = 0; k < padded; k += kLanes) {
    const Lanes w = load(real + k), t = (load(T + k) - mt) * w, v = (load(I + k) - mi) * w;
    tt += t * t, ii += v * v, ti += t * v;
  }
  const double var_t = total(tt), var_i = total(ii);
  return var_t > 0 && var_i > 0 ? total(ti) / std::sqrt(var_t * var_i) : 0.0;
}

}  // namespace

std::optional<cv::Point2f> alignWarpedTemplate(const cv::Mat& birth_image, cv::Point2f birth_pixel,
                                               const cv::Matx22d& warp, const cv::Mat& image,
                                               cv::Point2f initial,
                                               const TemplateAlignmentOptions& o) {
  const double det = cv::determinant(warp);
  if (!(std::abs(det) > 1e-6)) return std::nullopt;
  const cv::Matx22d to_birth = warp.inv();
  const int r = o.half_window, side = 2 * r + 1, wide = side + 2, n = side * side;
  // Template T(v) = I_birth(x_birth + W⁻¹ v) on the integer offsets v of the current image (one
  // pixel wider for its central-difference gradient). The map is affine: when the four corners
  // are inside, every sample is.
  const auto birthPoint = [&](int i, int j) {
    const cv::Vec2d u = to_birth * cv::Vec2d(i, j);
    return cv::Vec2d(birth_pixel.x + u[0], birth_pixel.y + u[1]);
  };
  for (const int j : {-r - 1, r + 1})
    for (const int i : {-r - 1, r + 1})
      if (const cv::Vec2d p = birthPoint(i, j); !inside(birth_image, p[0], p[1]))
        return std::nullopt;
  // Scratch reused across calls (no allocation per feature), one set per thread: the wide
  // template; the inner template, its gradient, the image patch and the weight of each sample
  // (1, 0 in the padding to a multiple of kLanes), row by row.
  const int padded = (n + kLanes - 1) / kLanes * kLanes;
  thread_local std::vector<float> wide_template, T, Tx, Ty, I, real;
  wide_template.resize(static_cast<size_t>(wide) * wide);
  for (auto* v : {&T, &Tx, &Ty, &I, &real}) v->assign(padded, 0.0f);
  std::fill(real.begin(), real.begin() + n, 1.0f);
  const cv::Vec2d column_step(to_birth(0, 0), to_birth(1, 0));
  for (int j = 0; j < wide; ++j)
    sampleLine(birth_image, birthPoint(-r - 1, j - r - 1), column_step, wide,
               &wide_template[static_cast<size_t>(j) * wide]);
  for (int j = 0; j < side; ++j) {
    const float* t = &wide_template[static_cast<size_t>(j + 1) * wide + 1];
    for (int i = 0; i < side; ++i) {
      T[j * side + i] = t[i];
      Tx[j * side + i] = 0.5f * (t[i + 1] - t[i - 1]);
      Ty[j * side + i] = 0.5f * (t[i + wide] - t[i - wide]);
    }
  }
  // Residual e(v) = I(x + v) − g T(v) − b; unknowns (x, y, g, b). Inverse-compositional style: the
  // Jacobian J = (∇T, −T, −1) is the template's, so the normal matrix Σ J Jᵀ is built once.
  Lanes xx{}, xy{}, xt{}, x1{}, yy{}, yt{}, y1{}, tt{}, t1{};
  for (int k = 0; k < padded; k += kLanes) {
    const Lanes gx = load(&Tx[k]), gy = load(&Ty[k]), t = load(&T[k]);
    xx += gx * gx, xy += gx * gy, xt += gx * t, x1 += gx;
    yy += gy * gy, yt += gy * t, y1 += gy;
    tt += t * t, t1 += t;
  }
  const cv::Matx44d H(total(xx), total(xy), -total(xt), -total(x1),  //
                      total(xy), total(yy), -total(yt), -total(y1),  //
                      -total(xt), -total(yt), total(tt), total(t1),  //
                      -total(x1), -total(y1), total(t1), static_cast<double>(n));
  cv::Matx44d H_inv;
  if (cv::invert(H, H_inv, cv::DECOMP_CHOLESKY) == 0) return std::nullopt;
  double x = initial.x, y = initial.y, gain = 1, offset = 0;
  for (int iteration = 0; iteration < o.max_iterations; ++iteration) {
    if (!inside(image, x - r, y - r) || !inside(image, x + r, y + r)) return std::nullopt;
    samplePatch(image, x - r, y - r, side, I.data());
    // Gauss–Newton gradient Σ e J.
    const float g = static_cast<float>(gain), b = static_cast<float>(offset);
    Lanes ex{}, ey{}, et{}, e1{};
    for (int k = 0; k < padded; k += kLanes) {
      const Lanes t = load(&T[k]), e = (load(&I[k]) - g * t - b) * load(&real[k]);
      ex += e * load(&Tx[k]), ey += e * load(&Ty[k]), et -= e * t, e1 -= e;
    }
    const cv::Vec4d grad(total(ex), total(ey), total(et), total(e1));
    const cv::Vec4d step = -(H_inv * grad);
    x += step[0] / gain;  // ∂e/∂x = ∇I ≈ g ∇T
    y += step[1] / gain;
    gain += step[2];
    offset += step[3];
    if (std::hypot(x - initial.x, y - initial.y) > r) return std::nullopt;
    if (std::hypot(step[0], step[1]) < o.converged_px) break;
  }
  // A patch that only matches with its contrast halved or doubled is not the same patch.
  if (gain < o.min_gain || gain > 1 / o.min_gain) return std::nullopt;
  // The last step may have moved the patch past the border.
  if (!inside(image, x - r, y - r) || !inside(image, x + r, y + r)) return std::nullopt;
  samplePatch(image, x - r, y - r, side, I.data());
  if (zeroMeanCorrelation(T.data(), I.data(), real.data(), n, padded) < o.min_correlation)
    return std::nullopt;
  return cv::Point2f(static_cast<float>(x), static_cast<float>(y));
}

cv::Matx22d homographyJacobian(const cv::Matx33d& H, cv::Point2f p) {
  const cv::Vec3d q = H * cv::Vec3d(p.x, p.y, 1);
  const double u = q[0] / q[2], v = q[1] / q[2];
  // ∂(q_xy / q_z)/∂p = (H_xy,xy − (u, v)ᵀ H_z,xy) / q_z
  return cv::Matx22d(H(0, 0) - u * H(2, 0), H(0, 1) - u * H(2, 1), H(1, 0) - v * H(2, 0),
                     H(1, 1) - v * H(2, 1)) *
         (1.0 / q[2]);
}

}  // namespace rpvio
