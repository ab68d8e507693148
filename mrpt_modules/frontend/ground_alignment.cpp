#include "mrpt_modules/frontend/ground_alignment.h"

#include <Eigen/Dense>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "mrpt_modules/frontend/point_undistortion.h"

namespace rpvio {
namespace {

constexpr double kMarginPx = 3;    // of a level's pixels, from the image's edge
constexpr double kCauchyGrey = 8;  // Cauchy scale: an error this large weighs half
// A prior holds n near the given down direction where the pixels do not fix it: seen at a grazing
// angle, the ground's flow changes little over the few degrees below the horizon, and a tilted n
// with a shorter a fits it almost as well. A tilt of kPriorSigmaRad costs as much as every pixel
// being kPriorGrey off.
constexpr double kPriorGrey = 1, kPriorSigmaRad = 5 * M_PI / 180;
double priorWeight(size_t pixels) {
  return static_cast<double>(pixels) * kPriorGrey * kPriorGrey / (kPriorSigmaRad * kPriorSigmaRad);
}

/// An 8-bit image at (u, v), bilinear; (u, v) at least one pixel inside the last row and column.
double sampleBilinear(const cv::Mat& image, double u, double v) {
  const int x = static_cast<int>(u), y = static_cast<int>(v);
  const double fx = u - x, fy = v - y;
  const uint8_t* top = image.ptr<uint8_t>(y) + x;
  const uint8_t* bottom = image.ptr<uint8_t>(y + 1) + x;
  return (1 - fy) * ((1 - fx) * top[0] + fx * top[1]) +
         fy * ((1 - fx) * bottom[0] + fx * bottom[1]);
}

// Cauchy's weight and cost: what is not the ground (a parked car, a curb) weighs little.
double cauchyWeight(double r) { return 1 / (1 + (r * r) / (kCauchyGrey * kCauchyGrey)); }
double robustCost(double r) {
  return 0.5 * kCauchyGrey * kCauchyGrey * std::log1p(r * r / (kCauchyGrey * kCauchyGrey));
}

/// Two unit vectors orthogonal to n and to each other.
Eigen::Matrix<double, 3, 2> tangentBasis(const Eigen::Vector3d& n) {
  const Eigen::Vector3d helper =
      std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  Eigen::Matrix<double, 3, 2> B;
  B.col(0) = n.cross(helper).normalized();
  B.col(1) = n.cross(B.col(0));
  return B;
}

}  // namespace

GreyPyramid buildGreyPyramid(const cv::Mat& image, int levels) {
  GreyPyramid pyramid{image};
  for (int l = 1; l < levels; ++l) {
    cv::Mat next;
    cv::pyrDown(pyramid.back(), next);
    pyramid.push_back(next);
  }
  return pyramid;
}

GroundAligner::GroundAligner(const CameraIntrinsics& camera, const GroundAlignmentOptions& options)
    : camera_(camera), options_(options) {}

std::vector<GroundAligner::Sample> GroundAligner::samples(const cv::Mat& previous, int level,
                                                          const Eigen::Vector3d& down) {
  if (normalized_.size() <= static_cast<size_t>(level)) normalized_.resize(level + 1);
  cv::Mat& lattice = normalized_[level];
  const double scale = 1 << level;
  if (lattice.size() != previous.size()) {
    std::vector<cv::Point2f> pixels;
    for (int v = 0; v < previous.rows; ++v)
      for (int u = 0; u < previous.cols; ++u)
        pixels.emplace_back(static_cast<float>(u * scale), static_cast<float>(v * scale));
    const std::vector<cv::Point2f> normalized = undistortToNormalized(pixels, camera_);
    lattice.create(previous.size(), CV_32FC2);
    for (size_t i = 0; i < normalized.size(); ++i)
      lattice.at<cv::Vec2f>(static_cast<int>(i) / previous.cols,
                            static_cast<int>(i) % previous.cols) = {normalized[i].x,
                                                                    normalized[i].y};
  }
  const double min_sine = std::sin(options_.horizon_margin_deg * M_PI / 180);
  const double min_gradient2 = options_.min_gradient * options_.min_gradient;
  const Eigen::Vector3d side = down.cross(Eigen::Vector3d::UnitZ()).normalized();
  std::vector<Sample> found;
  for (int v = 1; v + 1 < previous.rows; ++v) {
    const uint8_t* row = previous.ptr<uint8_t>(v);
    for (int u = 1; u + 1 < previous.cols; ++u) {
      const double gx = 0.5 * (row[u + 1] - row[u - 1]);
      const double gy = 0.5 * (previous.at<uint8_t>(v + 1, u) - previous.at<uint8_t>(v - 1, u));
      if (gx * gx + gy * gy < min_gradient2) continue;
      const cv::Vec2f& p = lattice.at<cv::Vec2f>(v, u);
      const Eigen::Vector3d x(p[0], p[1], 1);
      const double below = down.dot(x);
      if (below < min_sine * x.norm()) continue;  // above the horizon's margin
      // A ground point's offset to the side over the height: (x·side)/(x·down), side ⟂ down and
      // the optical axis.
      if (std::abs(x.dot(side)) > options_.corridor_heights * below) continue;
      found.push_back({x, static_cast<float>(row[u])});
    }
  }
  // At most max_pixels, evenly spread over the region (the cost is linear in them).
  if (found.size() > static_cast<size_t>(options_.max_pixels)) {
    std::vector<Sample> thinned;
    const double step = static_cast<double>(found.size()) / options_.max_pixels;
    for (double i = 0; i < found.size(); i += step)
      thinned.push_back(found[static_cast<size_t>(i)]);
    found = std::move(thinned);
  }
  return found;
}

bool GroundAligner::warp(const Eigen::Matrix3d& H, const Eigen::Vector3d& x, const cv::Mat& image,
                         int level, Eigen::Vector3d& y, Eigen::Vector2d& p) const {
  y = H * x;
  if (y.z() <= 1e-6) return false;
  p = distortToPixel(y.hnormalized(), camera_) / static_cast<double>(1 << level);
  return p.x() >= 0 && p.y() >= 0 && p.x() < image.cols - 1 && p.y() < image.rows - 1;
}

double GroundAligner::cost(const std::vector<Sample>& samples, const cv::Mat& current, int level,
                           const Eigen::Matrix3d& R, const GroundMotion& motion, double alpha,
                           double beta) const {
  const Eigen::Matrix3d H = motion.homography(R);
  double sum = 0;
  int count = 0;
  for (const Sample& s : samples) {
    Eigen::Vector3d y;
    Eigen::Vector2d p;
    if (!warp(H, s.x, current, level, y, p)) continue;
    const double r = sampleBilinear(current, p.x(), p.y()) - alpha * s.grey - beta;
    sum += robustCost(r);
    ++count;
  }
  sum += 0.5 * priorWeight(samples.size()) * (motion.n - down_).squaredNorm();
  // A pixel warped out of the image costs as much as one an error of the robust scale off:
  // less than a mismatch, more than a match, so that forward motion is not held back.
  const double outside = static_cast<double>(samples.size() - count);
  return sum + outside * robustCost(kCauchyGrey);
}

GroundAligner::Result GroundAligner::align(const GreyPyramid& previous, const GreyPyramid& current,
                                           const Eigen::Matrix3d& R, const Eigen::Vector3d& down,
                                           const GroundMotion* guess) {
  Result result;
  const int coarsest = options_.coarsest_level, finest = options_.finest_level;
  down_ = down;
  if (static_cast<int>(previous.size()) <= coarsest || current.size() != previous.size())
    return result;
  // Starting points on the coarsest level: the guess, standing still, and motions along the
  // camera's axes of 5 to 60 % of the ground's distance.
  std::vector<GroundMotion> starts;
  if (guess) starts.push_back(*guess);
  starts.push_back({Eigen::Vector3d::Zero(), down});
  for (double speed : {0.05, 0.1, 0.2, 0.35, 0.6})
    for (int axis = 0; axis < 3; ++axis)
      for (double sign : {-1.0, 1.0})
        starts.push_back({sign * speed * Eigen::Vector3d::Unit(axis), down});
  std::vector<Sample> coarse = samples(previous[coarsest], coarsest, down);
  if (coarse.empty()) return result;
  const double beta0 = cv::mean(current[coarsest])[0] - cv::mean(previous[coarsest])[0];
  GroundMotion motion = starts.front();
  double best = std::numeric_limits<double>::infinity();
  for (const GroundMotion& start : starts) {
    const double c = cost(coarse, current[coarsest], coarsest, R, start, 1, beta0);
    if (c < best) best = c, motion = start;
  }
  double alpha = 1, beta = beta0;

  std::vector<Sample> level_samples = std::move(coarse);
  for (int level = coarsest; level >= finest; --level) {
    if (level != coarsest) level_samples = samples(previous[level], level, down);
    const cv::Mat& image = current[level];
    // Only the pixels the level's starting motion keeps inside the image, with a margin: those
    // it sends out would pull the motion short to stay in (forward motion pushes the road's
    // lowest pixels out of the next image).
    const Eigen::Matrix3d H_start = motion.homography(R);
    std::vector<Sample> inside;
    for (const Sample& s : level_samples) {
      Eigen::Vector3d y;
      Eigen::Vector2d p;
      if (warp(H_start, s.x, image, level, y, p) && p.x() >= kMarginPx && p.y() >= kMarginPx &&
          p.x() < image.cols - 1 - kMarginPx && p.y() < image.rows - 1 - kMarginPx)
        inside.push_back(s);
    }
    level_samples = std::move(inside);
    const double scale = 1.0 / (1 << level);
    double current_cost = cost(level_samples, image, level, R, motion, alpha, beta);
    double lambda = 1e-3;
    for (int iteration = 0; iteration < options_.iterations; ++iteration) {
      // Normal equations of r = I_cur(π(H x)) − α I_prev(x) − β over (δa, δn, δα, δβ).
      Eigen::Matrix<double, 7, 7> A = Eigen::Matrix<double, 7, 7>::Zero();
      Eigen::Matrix<double, 7, 1> b = Eigen::Matrix<double, 7, 1>::Zero();
      const Eigen::Matrix3d H = motion.homography(R);
      const Eigen::Matrix<double, 3, 2> B = tangentBasis(motion.n);
      for (const Sample& s : level_samples) {
        Eigen::Vector3d y;
        Eigen::Vector2d p;
        if (!warp(H, s.x, image, level, y, p)) continue;
        const double r = sampleBilinear(image, p.x(), p.y()) - alpha * s.grey - beta;
        if (p.x() < 1 || p.y() < 1 || p.x() >= image.cols - 2 || p.y() >= image.rows - 2) continue;
        // The image's gradient there, by central differences (only where the samples land).
        const Eigen::RowVector2d g(0.5 * (sampleBilinear(image, p.x() + 1, p.y()) -
                                          sampleBilinear(image, p.x() - 1, p.y())),
                                   0.5 * (sampleBilinear(image, p.x(), p.y() + 1) -
                                          sampleBilinear(image, p.x(), p.y() - 1)));
        // ∂p/∂y of the pinhole projection (the lens distortion's share left out).
        Eigen::Matrix<double, 2, 3> dp;
        dp << camera_.fx / y.z(), 0, -camera_.fx * y.x() / (y.z() * y.z()), 0, camera_.fy / y.z(),
            -camera_.fy * y.y() / (y.z() * y.z());
        const Eigen::RowVector3d gdp = g * dp * scale;
        Eigen::Matrix<double, 1, 7> J;
        J.segment<3>(0) = gdp * motion.n.dot(s.x);                 // ∂y/∂a = (nᵀx) I
        J.segment<2>(3) = gdp * motion.a * (s.x.transpose() * B);  // ∂y/∂δn = a xᵀB
        J(5) = -s.grey;
        J(6) = -1;
        const double w = cauchyWeight(r);
        A.noalias() += w * J.transpose() * J;
        b.noalias() += w * J.transpose() * r;
      }
      const double prior = priorWeight(level_samples.size());
      A.block<2, 2>(3, 3) += prior * Eigen::Matrix2d::Identity();  // the prior on n
      b.segment<2>(3) += prior * B.transpose() * (motion.n - down_);
      bool improved = false;
      while (!improved && lambda < 1e6) {
        Eigen::Matrix<double, 7, 7> damped = A;
        damped.diagonal() += lambda * A.diagonal().cwiseMax(1e-9);
        const Eigen::Matrix<double, 7, 1> step = -damped.ldlt().solve(b);
        if (!step.allFinite()) break;
        GroundMotion next{motion.a + step.segment<3>(0),
                          (motion.n + B * step.segment<2>(3)).normalized()};
        const double next_cost =
            cost(level_samples, image, level, R, next, alpha + step(5), beta + step(6));
        if (next_cost < current_cost) {
          motion = next;
          alpha += step(5), beta += step(6);
          const double gain = current_cost - next_cost;
          current_cost = next_cost;
          lambda = std::max(lambda / 3, 1e-6);
          improved = true;
          if (gain < 1e-4 * current_cost) iteration = options_.iterations;  // converged
        } else {
          lambda *= 4;
        }
      }
      if (!improved) break;
    }
    if (level == finest) {
      double weighted = 0, weights = 0;
      int inliers = 0;
      const Eigen::Matrix3d H = motion.homography(R);
      std::vector<Sample> seen;  // the pixels the motion keeps in the image
      for (const Sample& s : level_samples) {
        Eigen::Vector3d y;
        Eigen::Vector2d p;
        if (!warp(H, s.x, image, level, y, p)) continue;
        seen.push_back(s);
        const double r = sampleBilinear(image, p.x(), p.y()) - alpha * s.grey - beta;
        weighted += cauchyWeight(r) * r * r;
        weights += cauchyWeight(r);
        if (std::abs(r) < kCauchyGrey) ++inliers;
      }
      result.residual_grey = weights > 0 ? std::sqrt(weighted / weights) : 0;
      // The same pixels without the ground's motion (the rotation alone): what the alignment
      // explains (over the pixels it keeps in view: sending pixels out is no explanation).
      const GroundMotion still{Eigen::Vector3d::Zero(), motion.n};
      result.still_cost_ratio = cost(seen, image, level, R, motion, alpha, beta) /
                                cost(seen, image, level, R, still, alpha, beta);
      result.pixels = static_cast<int>(seen.size());
      result.inlier_share = seen.empty() ? 0 : static_cast<double>(inliers) / seen.size();
    }
  }
  result.motion = motion;
  const double tilt = std::acos(std::clamp(motion.n.dot(down), -1.0, 1.0)) * 180 / M_PI;
  result.ok =
      result.pixels >= options_.min_pixels && result.inlier_share >= options_.min_inlier_share &&
      result.still_cost_ratio <= options_.max_still_cost_ratio &&
      result.residual_grey <= options_.max_residual_grey && tilt <= options_.max_normal_tilt_deg &&
      motion.a.allFinite() && motion.a.norm() <= options_.max_heights_per_image;
  return result;
}

}  // namespace rpvio
