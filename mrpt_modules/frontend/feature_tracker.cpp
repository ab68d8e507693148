#include "mrpt_modules/frontend/feature_tracker.h"

#include <Eigen/Core>  // before OpenCV's Eigen header, which needs it
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <opencv2/core/eigen.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>
#include <optional>
#include <unordered_map>

#include "common/input_error.h"
#include "mrpt_modules/frontend/homography_ransac.h"
#include "mrpt_modules/frontend/local_image_motion.h"
#include "mrpt_modules/frontend/motion_prediction.h"
#include "mrpt_modules/frontend/point_undistortion.h"
#include "mrpt_modules/frontend/warped_template_alignment.h"
#include "rawlog_io/uniform_plane_region.h"

namespace rpvio {
namespace {
const size_t kMinHomographyFeatures = 8;  // fewer (down to kMinAffineFeatures): an affine map
const size_t kMinAffineFeatures = 4;

/// The plane's image motion between consecutive frames, least squares over its inliers: a
/// homography, or an affine map on a small plane; nothing from fewer than kMinAffineFeatures.
std::optional<cv::Matx33d> planeImageMotion(const std::vector<cv::Point2f>& from,
                                            const std::vector<cv::Point2f>& to) {
  if (from.size() < kMinAffineFeatures) return std::nullopt;
  PointList a, b;
  for (const auto& p : from) a.emplace_back(p.x, p.y);
  for (const auto& p : to) b.emplace_back(p.x, p.y);
  const auto H = from.size() >= kMinHomographyFeatures ? fitHomography(a, b) : fitAffine(a, b);
  if (!H) return std::nullopt;
  cv::Matx33d motion;
  cv::eigen2cv(*H, motion);
  return motion;
}

/// Which labels the mask has at least one pixel of.
std::array<bool, 256> labelsIn(const cv::Mat& mask) {
  std::array<bool, 256> labelled{};
  for (int v = 0; v < mask.rows; ++v) {
    const uint8_t* row = mask.ptr<uint8_t>(v);
    for (int u = 0; u < mask.cols; ++u) labelled[row[u]] = true;
  }
  return labelled;
}

}  // namespace

void TrackerOptions::validate(const OptionsLoader& loader) const {
  loader.require(detection_level >= -1 && detection_level <= 3, "detection_level",
                 "must be 0 (full resolution) to 3, or -1 (by the image's width)");
  loader.require(frames_in_flight >= 1, "frames_in_flight", "must be at least 1");
  loader.require(ground_features >= 0, "ground_features", "must be 0 (none) or positive");
}

FeatureTracker::FeatureTracker(const CameraIntrinsics& camera, const TrackerOptions& options)
    : camera_(camera), options_(options) {
  if (options_.ground_features > 0)
    ground_.emplace(camera, GroundTrackOptions{options_.ground_features}, GroundAlignmentOptions{});
}

void FeatureTracker::undistort(std::vector<Track>& tracks) const {
  if (tracks.empty()) return;
  std::vector<cv::Point2f> pixels;
  for (const Track& tr : tracks) pixels.push_back(tr.pixel);
  const auto normalized = undistortToNormalized(pixels, camera_);
  for (size_t i = 0; i < tracks.size(); ++i) tracks[i].normalized = normalized[i];
}

void FeatureTracker::warnOnce(const std::string& message) {
  if (std::find(warned_.begin(), warned_.end(), message) != warned_.end()) return;
  warned_.push_back(message);
  warnings_.push_back(message);
}

std::vector<std::string> FeatureTracker::takeWarnings() {
  std::vector<std::string> out;
  out.swap(warnings_);
  return out;
}

std::vector<cv::Point2f> FeatureTracker::predictPixels(const Eigen::Matrix3d& R_cur_prev,
                                                       double dt) const {
  std::vector<cv::Point2f> pixels, normalized;
  for (const Track& tr : tracks_) {
    pixels.push_back(tr.pixel);
    normalized.push_back(tr.normalized);
  }
  std::vector<Eigen::Matrix3d> motion(tracks_.size(), R_cur_prev);
  // A velocity older than three of its intervals (frames dropped) predicts nothing.
  const double ratio = last_dt_ > 0 ? dt / last_dt_ : 0;
  if (options_.predict_plane_motion && last_rotation_ && ratio > 0 && ratio <= 3) {
    std::map<int, Eigen::Matrix3d> predicted;
    for (const auto& [plane, H_last] : plane_motions_)
      predicted[plane] = predictPlaneHomography(H_last, *last_rotation_, R_cur_prev, ratio);
    for (size_t i = 0; i < tracks_.size(); ++i)
      if (const auto it = predicted.find(tracks_[i].plane_id); it != predicted.end())
        motion[i] = it->second;
  }
  return predictUnderHomographies(pixels, normalized, motion, camera_);
}

std::vector<FeatureTracker::Track> FeatureTracker::propagate(const Pyramid& pyramid,
                                                             const cv::Mat& mask,
                                                             const Eigen::Matrix3d* R_cur_prev,
                                                             double dt) {
  std::vector<Track> kept;
  if (tracks_.empty() || previous_pyramid_.empty()) return kept;
  if (previous_pyramid_[0].size() != pyramid[0].size()) {
    warnOnce("image size changed: tracks restarted");
    return kept;
  }
  std::vector<cv::Point2f> from, to, back;
  for (const Track& tr : tracks_) from.push_back(tr.pixel);
  std::vector<uchar> status, back_status;
  const cv::Size window(options_.klt_window, options_.klt_window);
  const cv::TermCriteria stop(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 30, 0.003);
  // No error output: OpenCV then skips a pass over every window that computes it (4.7% of the
  // tracker's instructions; the tracks are the same).
  const bool predict = options_.predict_rotation && R_cur_prev;
  if (predict) to = predictPixels(*R_cur_prev, dt);
  cv::calcOpticalFlowPyrLK(previous_pyramid_, pyramid, from, to, status, cv::noArray(), window,
                           options_.klt_levels, stop, predict ? cv::OPTFLOW_USE_INITIAL_FLOW : 0,
                           options_.klt_min_eigenvalue);
  // The backward pass starts where a consistent track must end (its origin), so it needs no
  // coarse level: the full-resolution window converges from a few pixels away, and a track
  // more than max_forward_backward_px inconsistent is rejected anyway.
  back = from;
  cv::calcOpticalFlowPyrLK(pyramid, previous_pyramid_, to, back, back_status, cv::noArray(), window,
                           0, stop, cv::OPTFLOW_USE_INITIAL_FLOW, options_.klt_min_eigenvalue);
  const cv::Rect inside(1, 1, mask.cols - 2, mask.rows - 2);
  std::optional<std::array<bool, 256>> labelled;  // the mask's labels, once a track needs them
  for (size_t i = 0; i < tracks_.size(); ++i) {
    if (!status[i] || !back_status[i] || !inside.contains(to[i])) continue;
    if (cv::norm(back[i] - from[i]) > options_.max_forward_backward_px) continue;
    Track tr = tracks_[i];
    // The point must still lie on its own plane in the new mask, away from other surfaces; or
    // its plane is missing from the mask, for a few frames at most.
    if (options_.use_masks) {
      const cv::Point at(cvRound(to[i].x), cvRound(to[i].y));
      if (mask.at<uint8_t>(at) == tr.plane_id && trackable_.at<uint8_t>(at)) {
        tr.frames_plane_missed = 0;
      } else {
        if (!labelled) labelled = labelsIn(mask);
        if ((*labelled)[tr.plane_id] || ++tr.frames_plane_missed > options_.missed_plane_frames)
          continue;
      }
    }
    tr.from = tr.pixel;
    tr.pixel = to[i];
    ++tr.length;
    kept.push_back(tr);
  }
  return kept;
}

void FeatureTracker::refineAgainstAnchors(std::vector<Track>& tracks,
                                          const PlaneHomographies& homographies,
                                          const cv::Mat& image) const {
  TemplateAlignmentOptions alignment;
  alignment.half_window = options_.klt_window / 2;
  std::vector<Track> out;
  // The frame-to-frame motions before re-alignment: the neighbourhoods of local_warps.
  const bool neighbour_warps = !options_.use_masks && options_.local_warps;
  std::vector<PixelMotion> motions;
  if (neighbour_warps)
    for (const Track& tr : tracks) motions.push_back({tr.from, tr.pixel});
  for (size_t i = 0; i < tracks.size(); ++i) {
    Track& tr = tracks[i];
    // Local affine map of the plane's homography at the previous position; without masks, of
    // the neighbours' motion (local_warps); else the identity.
    const auto h = homographies.find(tr.plane_id);
    if (h != homographies.end())
      tr.warp = homographyJacobian(h->second, tr.from) * tr.warp;
    else if (neighbour_warps)
      if (const auto local = localImageMotion(motions, i, 8, 4 * options_.min_distance))
        tr.warp = *local * tr.warp;
    cv::Mat singular_values;
    cv::SVD::compute(tr.warp, singular_values, cv::SVD::NO_UV);
    const double largest = singular_values.at<double>(0), smallest = singular_values.at<double>(1);
    if (largest > options_.max_warp_scale || smallest < 1 / options_.max_warp_scale) continue;
    const auto aligned =
        alignWarpedTemplate(tr.anchor, tr.anchor_pixel, tr.warp, image, tr.pixel, alignment);
    // The anchored match must agree with the frame-to-frame one; otherwise the appearance has
    // changed too much since birth and the track ends.
    if (!aligned || cv::norm(*aligned - tr.pixel) > 1.0) continue;
    tr.pixel = *aligned;
    out.push_back(tr);
  }
  tracks.swap(out);
}

FeatureTracker::PlaneMotions FeatureTracker::rejectOutliers(std::vector<Track>& tracks) const {
  // Group by plane (one group without masks), test each group against its own model.
  std::map<int, std::vector<size_t>> groups;
  for (size_t i = 0; i < tracks.size(); ++i)
    groups[options_.use_masks ? tracks[i].plane_id : 0].push_back(i);
  std::unordered_map<int, cv::Point2f> previous_normalized;
  for (const Track& p : tracks_) previous_normalized[p.id] = p.normalized;
  std::vector<bool> keep(tracks.size(), true);
  PlaneMotions motions;
  RansacOptions ransac;
  ransac.threshold_px = options_.ransac_threshold_px;
  ransac.virtual_focal = options_.virtual_focal;
  for (const auto& [plane, indices] : groups) {
    std::vector<cv::Point2f> from, to;
    for (size_t i : indices) {
      from.push_back(previous_normalized.at(tracks[i].id));
      to.push_back(tracks[i].normalized);
    }
    const std::vector<bool> inliers = options_.use_masks ? homographyInliers(from, to, ransac)
                                                         : fundamentalInliers(from, to, ransac);
    std::vector<cv::Point2f> inlier_from, inlier_to;
    PointList normalized_from, normalized_to;
    for (size_t k = 0; k < indices.size(); ++k) {
      keep[indices[k]] = inliers[k];
      if (!inliers[k]) continue;
      inlier_from.push_back(tracks[indices[k]].from);
      inlier_to.push_back(tracks[indices[k]].pixel);
      normalized_from.emplace_back(from[k].x, from[k].y);
      normalized_to.emplace_back(to[k].x, to[k].y);
    }
    if (!options_.use_masks) continue;
    // The plane's image motion in pixels warps the birth patches of its tracks; undistorted, it
    // predicts the next frame's (predict_plane_motion).
    if (const auto motion = planeImageMotion(inlier_from, inlier_to))
      motions.pixels[plane] = *motion;
    if (options_.predict_plane_motion && normalized_from.size() >= kMinHomographyFeatures)
      if (const auto H = fitHomography(normalized_from, normalized_to))
        motions.normalized[plane] = *H;
  }
  std::vector<Track> out;
  for (size_t i = 0; i < tracks.size(); ++i)
    if (keep[i]) out.push_back(tracks[i]);
  tracks.swap(out);
  return motions;
}

void FeatureTracker::computeUniformRegions(const cv::Mat& mask) {
  if (!options_.use_masks) {
    detectable_ = cv::Mat(mask.size(), CV_8U, cv::Scalar(255));
    trackable_ = detectable_;
    return;
  }
  uniformPlaneRegion(mask, 2 * options_.window_margin + 1, 1, lowest_label_, highest_label_,
                     trackable_);
  // Trackable pixels are uniform over the window margin; an erosion reaching no further changes
  // nothing.
  const int erosion_reach = options_.erosion_kernel / 2 * options_.erosion_iterations;
  if (erosion_reach <= options_.window_margin) {
    detectable_ = trackable_;
    return;
  }
  uniformPlaneRegion(mask, options_.erosion_kernel, options_.erosion_iterations, lowest_label_,
                     highest_label_, detectable_);
  detectable_ &= trackable_;
}

int FeatureTracker::detectionLevel(int width) const {
  if (options_.detection_level >= 0) return options_.detection_level;
  int level = 0;
  while (level < 3 && (width >> (level + 1)) >= TrackerOptions::kAutoDetectionWidth) ++level;
  return level;
}

std::vector<cv::Point2f> FeatureTracker::detectCorners(CornerDetector& detector,
                                                       const cv::Mat& image, const cv::Mat& allowed,
                                                       int wanted, double spacing, int level,
                                                       const Pyramid* pyramid) const {
  // Shi–Tomasi corners on pyramid level `level`: a corner there is a textured neighbourhood of
  // 3·2^level px, which a KLT window of 21 px tracks as well as a full-resolution one, at a
  // quarter of the cost per level. The KLT pyramid's levels are the same pyrDown images (same
  // kernel and border) when it is the whole image's.
  cv::Mat level_image = image, level_allowed = allowed;
  for (int l = 0; l < level; ++l) {
    const size_t in_pyramid = 2 * static_cast<size_t>(l + 1);  // images and derivatives interleave
    if (pyramid && in_pyramid < pyramid->size())
      level_image = (*pyramid)[in_pyramid];
    else
      cv::pyrDown(level_image, level_image);
    cv::resize(level_allowed, level_allowed, level_image.size(), 0, 0, cv::INTER_NEAREST);
  }
  const double scale = std::ldexp(1.0, level);
  std::vector<cv::Point2f> corners =
      detector.detect(level_image, level_allowed, wanted, 0.01, std::max(1.0, spacing / scale));
  // Level pixel (x, y) is centred on base pixel (2^level x, 2^level y) (pyrDown's kernel).
  for (cv::Point2f& c : corners) c *= scale;
  return corners;
}

std::vector<cv::Point2f> FeatureTracker::detectInSparseCells(
    const cv::Mat& image, cv::Mat& allowed, const std::vector<cv::Point2f>& corners,
    const std::vector<Track>& kept, int wanted, int level) {
  const int side = options_.detection_cell_px;
  const int columns = (image.cols + side - 1) / side, rows = (image.rows + side - 1) / side;
  std::vector<int> in_cell(static_cast<size_t>(columns) * rows, 0);
  const auto count = [&](const cv::Point2f& p) {
    const int c = std::clamp(static_cast<int>(p.x) / side, 0, columns - 1);
    const int r = std::clamp(static_cast<int>(p.y) / side, 0, rows - 1);
    ++in_cell[static_cast<size_t>(r) * columns + c];
  };
  for (const Track& tr : kept) count(tr.pixel);  // `allowed` already keeps their neighbourhoods
  for (const cv::Point2f& p : corners) {
    count(p);
    cv::circle(allowed, p, static_cast<int>(options_.min_distance), cv::Scalar(0), cv::FILLED);
  }
  // A cell starts on the detection level's pixel lattice, as the whole image does.
  const int step = 1 << level;
  std::vector<cv::Point2f> found;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns && wanted > 0; ++c) {
      const int missing =
          options_.min_cell_features - in_cell[static_cast<size_t>(r) * columns + c];
      if (missing <= 0) continue;
      const cv::Rect cell = cv::Rect(c * side / step * step, r * side / step * step, side, side) &
                            cv::Rect(0, 0, image.cols, image.rows);
      if (cell.width < 2 * step || cell.height < 2 * step || cv::countNonZero(allowed(cell)) == 0)
        continue;
      const cv::Mat cell_allowed = allowed(cell);
      for (cv::Point2f corner :
           detectCorners(cell_detector_, image(cell), cell_allowed, std::min(missing, wanted),
                         options_.min_distance, level)) {
        corner += cv::Point2f(cell.tl());
        found.push_back(corner);
        --wanted;
        // Corners of the next cells keep min_distance from it too.
        cv::circle(allowed, corner, static_cast<int>(options_.min_distance), cv::Scalar(0),
                   cv::FILLED);
      }
    }
  return found;
}

cv::Mat& FeatureTracker::detectionMask(const cv::Mat& taken) {
  cv::Mat& allowed = allowed_;
  detectable_.copyTo(allowed);
  allowed.setTo(0, taken);
  // Corners whose birth patch would leave the image could not be anchored.
  const int border = std::min({options_.klt_window / 2 + 2, allowed.cols / 2, allowed.rows / 2});
  allowed.rowRange(0, border) = 0;
  allowed.rowRange(allowed.rows - border, allowed.rows) = 0;
  allowed.colRange(0, border) = 0;
  allowed.colRange(allowed.cols - border, allowed.cols) = 0;
  return allowed;
}

FeatureTracker::Track FeatureTracker::newTrack(int label, cv::Point2f corner,
                                               cv::Point2f normalized, const cv::Mat& image) {
  // The template (half side r + 1 with its gradient border) warped by at most max_warp_scale
  // (refineAgainstAnchors ends tracks beyond it) reaches max_warp_scale·(r + 1)·√2 px from the
  // birth pixel, and bilinear sampling one pixel more. A copy of that much of the birth image is
  // kept per track: compact in memory (a whole frame per birth image is not) and samples the
  // same pixels.
  const int reach = static_cast<int>(std::ceil(options_.max_warp_scale *
                                               (options_.klt_window / 2 + 1) * std::sqrt(2.0))) +
                    1;
  const cv::Point birth(cvRound(corner.x), cvRound(corner.y));
  const cv::Rect patch = cv::Rect(birth.x - reach, birth.y - reach, 2 * reach + 1, 2 * reach + 1) &
                         cv::Rect(0, 0, image.cols, image.rows);
  // Corners lie on integer pixels: the shift to the patch's pixels is exact.
  const cv::Point2f in_patch =
      corner - cv::Point2f(static_cast<float>(patch.x), static_cast<float>(patch.y));
  return {next_id_++, label, 1, corner, normalized, image(patch).clone(), in_patch, corner};
}

FeatureFrame FeatureTracker::publish(double t, double dt) {
  FeatureFrame frame;
  frame.t = frame.image_t = t;
  std::unordered_map<int, cv::Point2f> previous_normalized;
  for (const Track& p : previous_) previous_normalized[p.id] = p.normalized;
  for (const Track& tr : tracks_) {
    TrackedFeature f;
    f.id = tr.id;
    f.plane_id = tr.plane_id;
    f.pixel = {tr.pixel.x, tr.pixel.y};
    f.normalized = {tr.normalized.x, tr.normalized.y};
    f.track_length = tr.length;
    const auto prev = previous_normalized.find(tr.id);
    if (prev != previous_normalized.end() && dt > 0)
      f.velocity = {(tr.normalized.x - prev->second.x) / dt,
                    (tr.normalized.y - prev->second.y) / dt};
    frame.features.push_back(f);
  }
  return frame;
}

FeatureFrame FeatureTracker::track(double t, const cv::Mat& raw_image, const cv::Mat& raw_mask,
                                   const Eigen::Matrix3d* R_cur_prev, const Eigen::Vector3d* down) {
  const double dt = previous_pyramid_.empty() ? 0 : t - previous_t_;
  cv::Mat image = raw_image, mask = raw_mask;
  bool usable = true;
  if (image.empty() || image.type() != CV_8UC1) {
    warnOnce("image empty or not 8-bit grey: no features");
    usable = false;
  } else if (options_.use_masks &&
             (mask.empty() || mask.size() != image.size() || mask.type() != CV_8UC1)) {
    warnOnce("plane mask missing or of another size than its image: no features");
    usable = false;
  }
  if (!usable) {
    tracks_.clear();
    previous_.clear();
    previous_pyramid_.clear();
    plane_motions_.clear();
    last_rotation_.reset();
    if (ground_)
      ground_.emplace(camera_, GroundTrackOptions{options_.ground_features},
                      GroundAlignmentOptions{});
    return FeatureFrame{t, t, {}};
  }
  if (options_.clahe) {
    cv::Mat equalized;
    cv::createCLAHE(3.0, cv::Size(8, 8))->apply(image, equalized);
    image = equalized;
  }
  if (!options_.use_masks) mask = cv::Mat(image.size(), CV_8U, cv::Scalar(0));

  computeUniformRegions(mask);
  cv::buildOpticalFlowPyramid(image, pyramid_, cv::Size(options_.klt_window, options_.klt_window),
                              options_.klt_levels, true);
  std::vector<Track> kept = propagate(pyramid_, mask, R_cur_prev, dt);
  undistort(kept);
  PlaneMotions motions = rejectOutliers(kept);
  plane_motions_ = std::move(motions.normalized);
  if (R_cur_prev)
    last_rotation_ = *R_cur_prev;
  else
    last_rotation_.reset();
  last_dt_ = dt;
  if (options_.anchor_refinement) {
    refineAgainstAnchors(kept, motions.pixels, image);
    undistort(kept);
  }
  const std::map<int, DensePlane> dense =
      options_.use_masks ? densePlanes(mask, detectable_, options_.min_plane_features,
                                       options_.min_distance, options_.klt_window)
                         : std::map<int, DensePlane>{};
  const auto spacingOf = [&](int label) {
    const auto it = dense.find(label);
    return it == dense.end() ? options_.min_distance : it->second.spacing;
  };
  // Longest tracks first: they claim their neighbourhood before shorter ones.
  std::stable_sort(kept.begin(), kept.end(),
                   [](const Track& a, const Track& b) { return a.length > b.length; });
  std::vector<Track> spaced;
  std::map<int, int> tracks_on_plane;
  cv::Mat& taken = taken_;
  taken.create(image.size(), CV_8U);
  taken.setTo(0);
  for (const Track& tr : kept) {
    if (taken.at<uint8_t>(cvRound(tr.pixel.y), cvRound(tr.pixel.x))) continue;
    spaced.push_back(tr);
    ++tracks_on_plane[tr.plane_id];
    cv::circle(taken, tr.pixel, static_cast<int>(spacingOf(tr.plane_id)), cv::Scalar(255),
               cv::FILLED);
  }

  int wanted = options_.max_features - static_cast<int>(spaced.size());
  if (wanted > 0) {
    cv::Mat& allowed = detectionMask(taken);
    const int level = detectionLevel(image.cols);
    const bool any_allowed = cv::countNonZero(allowed) > 0;
    std::vector<cv::Point2f> corners;
    // The dense planes first, each up to min_plane_features, on its own box and label; then the
    // other planes (a dense plane gets no more corners at the wider spacing).
    const int step = 1 << level;  // a detection-level pixel, in base pixels
    for (const auto& [label, plane] : dense) {
      // The box starts on the detection level's pixel lattice, as the whole image's does.
      const cv::Point corner(plane.box.x / step * step, plane.box.y / step * step);
      const cv::Rect box(corner, plane.box.br());  // from one corner to the other
      cv::compare(mask(box), label, on_plane_, cv::CMP_EQ);
      on_plane_ &= allowed(box);
      const int on_plane = std::min(wanted, options_.min_plane_features - tracks_on_plane[label]);
      if (on_plane > 0) {
        auto found =
            detectCorners(plane_detector_, image(box), on_plane_, on_plane, plane.spacing, level);
        for (cv::Point2f& c : found) c += cv::Point2f(box.tl());
        corners.insert(corners.end(), found.begin(), found.end());
        wanted -= static_cast<int>(found.size());
      }
      allowed(box).setTo(0, on_plane_);
    }
    if (wanted > 0 && any_allowed) {
      auto found =
          detectCorners(detector_, image, allowed, wanted, options_.min_distance, level, &pyramid_);
      corners.insert(corners.end(), found.begin(), found.end());
      wanted -= static_cast<int>(found.size());
    }
    if (wanted > 0 && any_allowed && options_.detection_cell_px > 0) {
      const auto found = detectInSparseCells(image, allowed, corners, spaced, wanted, level);
      corners.insert(corners.end(), found.begin(), found.end());
    }
    if (!any_allowed && spaced.empty())
      warnOnce("no static plane visible in the mask: no features (waiting for planes)");
    else if (corners.empty() && spaced.empty())
      warnOnce("no corners found in the image");
    const auto normalized = undistortToNormalized(corners, camera_);
    for (size_t i = 0; i < corners.size(); ++i) {
      const int label = options_.use_masks
                            ? raw_mask.at<uint8_t>(cvRound(corners[i].y), cvRound(corners[i].x))
                            : 0;
      spaced.push_back(newTrack(label, corners[i], normalized[i], image));
    }
  }
  previous_ = tracks_;
  tracks_ = spaced;
  std::swap(previous_pyramid_, pyramid_);
  previous_t_ = t;
  FeatureFrame frame = publish(t, dt);
  if (ground_) {
    const auto ground = ground_->track(t, image, R_cur_prev, down, next_id_);
    frame.features.insert(frame.features.end(), ground.begin(), ground.end());
  }
  return frame;
}

}  // namespace rpvio
