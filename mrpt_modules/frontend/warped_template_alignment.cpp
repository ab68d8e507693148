#include "mrpt_modules/frontend/warped_template_alignment.h"

#include <cmath>
#include <vector>

namespace rpvio {
namespace {

/// Bilinear sample of a CV_8UC1 image; the caller keeps (x, y) inside [0, cols−1) × [0, rows−1).
double sample(const cv::Mat& image, double x, double y) {
  const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
  const double ax = x - x0, ay = y - y0;
  const uint8_t* row0 = image.ptr<uint8_t>(y0) + x0;
  const uint8_t* row1 = image.ptr<uint8_t>(y0 + 1) + x0;
  return (1 - ay) * ((1 - ax) * row0[0] + ax * row0[1]) + ay * ((1 - ax) * row1[0] + ax * row1[1]);
}

bool inside(const cv::Mat& image, double x, double y) {
  return x >= 0 && y >= 0 && x < image.cols - 1 && y < image.rows - 1;
}

/// The side x side image samples I(x + i, y + j), i, j = 0..side−1, into `out`; every sample shares
/// the fractional part of (x, y): one set of bilinear weights. The caller keeps the patch inside.
void samplePatch(const cv::Mat& image, double x, double y, int side, std::vector<double>& out) {
  const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
  const double ax = x - x0, ay = y - y0;
  const double w00 = (1 - ax) * (1 - ay), w01 = ax * (1 - ay), w10 = (1 - ax) * ay, w11 = ax * ay;
  out.resize(static_cast<size_t>(side) * side);
  for (int j = 0; j < side; ++j) {
    const uint8_t* row0 = image.ptr<uint8_t>(y0 + j) + x0;
    const uint8_t* row1 = image.ptr<uint8_t>(y0 + j + 1) + x0;
    double* I = &out[static_cast<size_t>(j) * side];
    for (int i = 0; i < side; ++i)
      I[i] = w00 * row0[i] + w01 * row0[i + 1] + w10 * row1[i] + w11 * row1[i + 1];
  }
}

/// Zero-mean normalized cross-correlation of the template's inner side² samples (row stride
/// `wide`, one-pixel border) with the image samples I (row stride side).
double zeroMeanCorrelation(const std::vector<double>& T, int wide, const std::vector<double>& I,
                           int side) {
  double st = 0, si = 0, stt = 0, sii = 0, sti = 0;
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i) {
      const double t = T[(j + 1) * wide + i + 1], v = I[j * side + i];
      st += t, si += v, stt += t * t, sii += v * v, sti += t * v;
    }
  const double n = side * side;
  const double var_t = stt - st * st / n, var_i = sii - si * si / n;
  return var_t > 0 && var_i > 0 ? (sti - st * si / n) / std::sqrt(var_t * var_i) : 0.0;
}

}  // namespace

std::optional<cv::Point2f> alignWarpedTemplate(const cv::Mat& birth_image, cv::Point2f birth_pixel,
                                               const cv::Matx22d& warp, const cv::Mat& image,
                                               cv::Point2f initial,
                                               const TemplateAlignmentOptions& o) {
  const double det = cv::determinant(warp);
  if (!(std::abs(det) > 1e-6)) return std::nullopt;
  const cv::Matx22d to_birth = warp.inv();
  const int r = o.half_window, side = 2 * r + 1, wide = side + 2;
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
  // Scratch reused across calls (no allocation per feature), one set per thread.
  thread_local std::vector<double> T, Tx, Ty, I;
  T.resize(static_cast<size_t>(wide) * wide);
  for (int j = -r - 1; j <= r + 1; ++j)
    for (int i = -r - 1; i <= r + 1; ++i) {
      const cv::Vec2d p = birthPoint(i, j);
      T[(j + r + 1) * wide + i + r + 1] = sample(birth_image, p[0], p[1]);
    }
  // Residual e(v) = I(x + v) − g T(v) − b; unknowns (x, y, g, b). Inverse-compositional style: the
  // Jacobian J = (∇T, −T, −1) is the template's, so the normal matrix Σ J Jᵀ is built once.
  const size_t n = static_cast<size_t>(side) * side;
  Tx.resize(n);
  Ty.resize(n);
  double xx = 0, xy = 0, xt = 0, x1 = 0, yy = 0, yt = 0, y1 = 0, tt = 0, t1 = 0;
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i) {
      const double* t = &T[(j + 1) * wide + i + 1];
      const double gx = 0.5 * (t[1] - t[-1]), gy = 0.5 * (t[wide] - t[-wide]);
      Tx[j * side + i] = gx;
      Ty[j * side + i] = gy;
      xx += gx * gx, xy += gx * gy, xt += gx * t[0], x1 += gx;
      yy += gy * gy, yt += gy * t[0], y1 += gy;
      tt += t[0] * t[0], t1 += t[0];
    }
  const cv::Matx44d H(xx, xy, -xt, -x1,  //
                      xy, yy, -yt, -y1,  //
                      -xt, -yt, tt, t1,  //
                      -x1, -y1, t1, static_cast<double>(n));
  cv::Matx44d H_inv;
  if (cv::invert(H, H_inv, cv::DECOMP_CHOLESKY) == 0) return std::nullopt;
  double x = initial.x, y = initial.y, gain = 1, offset = 0;
  for (int iteration = 0; iteration < o.max_iterations; ++iteration) {
    if (!inside(image, x - r, y - r) || !inside(image, x + r, y + r)) return std::nullopt;
    samplePatch(image, x - r, y - r, side, I);
    // Gauss–Newton gradient Σ e J.
    double gx = 0, gy = 0, gt = 0, g1 = 0;
    for (int j = 0; j < side; ++j) {
      const double* t = &T[(j + 1) * wide + 1];
      const double* Ij = &I[j * side];
      const double* Txj = &Tx[j * side];
      const double* Tyj = &Ty[j * side];
      for (int i = 0; i < side; ++i) {
        const double e = Ij[i] - gain * t[i] - offset;
        gx += e * Txj[i], gy += e * Tyj[i], gt -= e * t[i], g1 -= e;
      }
    }
    const cv::Vec4d g(gx, gy, gt, g1);
    const cv::Vec4d step = -(H_inv * g);
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
  samplePatch(image, x - r, y - r, side, I);
  if (zeroMeanCorrelation(T, wide, I, side) < o.min_correlation) return std::nullopt;
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
