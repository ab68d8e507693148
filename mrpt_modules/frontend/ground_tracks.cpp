#include "mrpt_modules/frontend/ground_tracks.h"

#include <cmath>

#include "mrpt_modules/frontend/point_undistortion.h"

namespace rpvio {
namespace {

constexpr int kBorderPx = 8;  // a track ends this close to the image's edge

double angleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180 / M_PI;
}

/// A ground point as the front-end publishes it.
TrackedFeature feature(const GroundTracks::Point& p, const Eigen::Vector2d& velocity) {
  TrackedFeature f;
  f.id = p.id;
  f.plane_id = kGroundLabel;
  f.pixel = p.pixel;
  f.normalized = p.normalized;
  f.velocity = velocity;
  f.track_length = p.length;
  return f;
}

}  // namespace

GroundTracks::GroundTracks(const CameraIntrinsics& camera, const GroundTrackOptions& options,
                           const GroundAlignmentOptions& alignment)
    : camera_(camera),
      options_(options),
      alignment_options_(alignment),
      aligner_(camera, alignment) {}

bool GroundTracks::belowHorizon(const Eigen::Vector2d& x, const Eigen::Vector3d& down,
                                double margin_deg) const {
  const Eigen::Vector3d bearing = x.homogeneous();
  return down.dot(bearing) >= std::sin(margin_deg * M_PI / 180) * bearing.norm();
}

std::vector<TrackedFeature> GroundTracks::track(double t, const cv::Mat& image,
                                                const Eigen::Matrix3d* R_cur_prev,
                                                const Eigen::Vector3d* down, int& next_id) {
  GreyPyramid pyramid = buildGreyPyramid(image, alignment_options_.coarsest_level + 1);
  const double dt = t - previous_t_;
  last_.reset();
  std::optional<Eigen::Vector3d> ground_down;  // the ground's normal in this camera, if aligned
  // Down in the previous camera: gravity, else the ground's normal as last aligned.
  const std::optional<Eigen::Vector3d> down_before =
      previous_down_ ? previous_down_ : (motion_ ? std::optional(motion_->n) : std::nullopt);
  if (R_cur_prev && down_before && !previous_.empty() && dt > 0) {
    GroundMotion guess;
    if (motion_) guess = {*R_cur_prev * motion_->a, motion_->n};
    last_ =
        aligner_.align(previous_, pyramid, *R_cur_prev, *down_before, motion_ ? &guess : nullptr);
    // The plane found must be level with gravity as the IMU sees it (not a wall or a car's side).
    if (last_->ok && previous_down_ &&
        angleDeg(last_->motion.n, *previous_down_) > alignment_options_.max_normal_tilt_deg)
      last_->ok = false;
  }
  std::vector<TrackedFeature> published;
  if (last_ && last_->ok) {
    const GroundMotion& m = last_->motion;
    const Eigen::Matrix3d H = m.homography(*R_cur_prev);
    const Eigen::Vector3d n_cur = *R_cur_prev * m.n;  // the ground's normal in this camera
    ground_down = n_cur;
    // Constant velocity: the next translation over this camera's distance, d_k = d_(k-1)(1 + nₖᵀa).
    motion_ = GroundMotion{m.a / std::max(1 + n_cur.dot(m.a), 0.1), n_cur};
    std::vector<Point> kept;
    for (const Point& p : points_) {
      const Eigen::Vector3d y = H * p.normalized.homogeneous();
      if (y.z() <= 1e-6 || p.length >= options_.max_length) continue;
      const Eigen::Vector2d x = y.hnormalized();
      const Eigen::Vector2d pixel = distortToPixel(x, camera_);
      if (pixel.x() < kBorderPx || pixel.y() < kBorderPx || pixel.x() >= image.cols - kBorderPx ||
          pixel.y() >= image.rows - kBorderPx ||
          !belowHorizon(x, n_cur, alignment_options_.horizon_margin_deg))
        continue;
      kept.push_back({p.id, pixel, x, p.length + 1});
      published.push_back(feature(kept.back(), (x - p.normalized) / dt));
    }
    points_ = std::move(kept);
  } else {
    points_.clear();
    motion_.reset();
  }
  if (!ground_down && down) ground_down = *down;
  if (ground_down) {
    const size_t before = points_.size();
    spawn(image.size(), *ground_down, next_id);
    for (size_t i = before; i < points_.size(); ++i)
      published.push_back(feature(points_[i], Eigen::Vector2d::Zero()));
  }
  previous_ = std::move(pyramid);
  previous_t_ = t;
  previous_down_.reset();
  if (down) previous_down_ = *down;
  return published;
}

void GroundTracks::spawn(const cv::Size& size, const Eigen::Vector3d& down, int& next_id) {
  if (static_cast<int>(points_.size()) >= options_.features) return;
  // Candidates on a lattice below the horizon (a little further below than where tracks end, so
  // they live a few frames), taken farthest from the tracks first.
  std::vector<cv::Point2f> lattice;
  const double step = options_.spacing_px / 2;
  for (double v = kBorderPx + step / 2; v < size.height - kBorderPx; v += step)
    for (double u = kBorderPx + step / 2; u < size.width - kBorderPx; u += step)
      lattice.emplace_back(static_cast<float>(u), static_cast<float>(v));
  const std::vector<cv::Point2f> normalized = undistortToNormalized(lattice, camera_);
  std::vector<Point> candidates;
  for (size_t i = 0; i < lattice.size(); ++i) {
    const Eigen::Vector2d x(normalized[i].x, normalized[i].y);
    if (belowHorizon(x, down, alignment_options_.horizon_margin_deg + 2))
      candidates.push_back({-1, Eigen::Vector2d(lattice[i].x, lattice[i].y), x, 1});
  }
  const auto clearance = [&](const Point& c) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const Point& p : points_) nearest = std::min(nearest, (p.pixel - c.pixel).norm());
    return nearest;
  };
  while (static_cast<int>(points_.size()) < options_.features && !candidates.empty()) {
    size_t best = 0;
    double best_clearance = -1;
    for (size_t i = 0; i < candidates.size(); ++i) {
      const double c = clearance(candidates[i]);
      if (c > best_clearance) best_clearance = c, best = i;
    }
    if (best_clearance < options_.spacing_px) break;
    Point p = candidates[best];
    p.id = next_id++;
    points_.push_back(p);
    candidates.erase(candidates.begin() + static_cast<long>(best));
  }
}

}  // namespace rpvio
