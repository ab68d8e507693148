#include "mrpt_modules/loop/loop_detector.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace rpvio {

std::optional<LoopEvent> LoopDetector::add(double t, const Eigen::Isometry3d& body,
                                           KeyframeAppearance appearance) {
  path_.push_back(keyframes_.size() > map_keyframes_
                      ? path_.back() +
                            (body.translation() - keyframes_.back().body.translation()).norm()
                      : 0.0);
  keyframes_.push_back({t, body, std::move(appearance)});
  if (next_training_ == 0) next_training_ = options_.loop_vocabulary_keyframes;
  if (keyframes_.size() >= next_training_) {
    trainVocabulary();  // the newest keyframe is in the rebuilt database
    next_training_ = 2 * keyframes_.size();
    return query(database_.vector(keyframes_.size() - 1));
  }
  if (vocabulary_.empty()) return std::nullopt;
  const BowVector bow = vocabulary_.transform(keyframes_.back().appearance.descriptors);
  std::optional<LoopEvent> event = query(bow);
  database_.add(bow);
  return event;
}

void LoopDetector::trainVocabulary() {
  size_t total = 0;
  for (const StoredKeyframe& k : keyframes_) total += k.appearance.descriptors.rows;
  const size_t stride =
      std::max<size_t>(1, (total + options_.loop_vocabulary_descriptors - 1) /
                              std::max<size_t>(options_.loop_vocabulary_descriptors, 1));
  std::vector<cv::Mat> images;
  size_t row = 0;
  for (const StoredKeyframe& k : keyframes_) {
    cv::Mat sampled;
    for (int r = 0; r < k.appearance.descriptors.rows; ++r, ++row)
      if (row % stride == 0) sampled.push_back(k.appearance.descriptors.row(r));
    images.push_back(sampled);
  }
  vocabulary_ = BinaryVocabulary::train(images, options_.vocabulary);
  database_.clear();
  for (const StoredKeyframe& k : keyframes_)
    database_.add(vocabulary_.transform(k.appearance.descriptors));
}

std::optional<LoopEvent> LoopDetector::query(const BowVector& bow) {
  const StoredKeyframe& newest = keyframes_.back();
  const size_t index = keyframes_.size() - 1;  // the database holds the keyframes before it
  // Candidates: the map's keyframes and the run's old enough, scoring at least a share of what the
  // previous keyframe of the run scores (DBoW2's normalization: a score's scale depends on the
  // place and the vocabulary; the run's first keyframe has no reference, the check decides).
  const auto session = keyframes_.begin() + static_cast<std::ptrdiff_t>(map_keyframes_);
  const auto old_enough =
      std::upper_bound(session, keyframes_.end() - 1, newest.t - options_.loop_min_age_s,
                       [](double t, const StoredKeyframe& k) { return t < k.t; });
  const size_t before = static_cast<size_t>(old_enough - keyframes_.begin());
  if (before == 0) return std::nullopt;
  const double reference =
      index > map_keyframes_ ? bowScore(bow, database_.vector(index - 1)) : 0.0;
  const auto matches = database_.query(bow, before, options_.loop_min_score_ratio * reference);
  if (matches.empty()) return std::nullopt;
  LoopEvent event;
  for (int c = 0; c < std::min<int>(options_.loop_candidates, static_cast<int>(matches.size()));
       ++c) {
    const StoredKeyframe& old = keyframes_[matches[c].keyframe];
    LoopCheck check =
        verifyLoop(newest.appearance, old.appearance, old.body, T_BC_, options_.check);
    const double baseline = (newest.body.inverse() * check.old_body).translation().norm();
    if (check.accepted && options_.loop_max_baseline_m > 0 &&
        baseline > options_.loop_max_baseline_m) {
      check.accepted = false;
      check.why = "baseline " + std::to_string(baseline).substr(0, 4) + " m";
    }
    if (check.accepted && matches[c].keyframe >= map_keyframes_)
      checkDrift(matches[c].keyframe, check);
    if (c == 0 || check.accepted) {
      event.t = newest.t;
      event.t_old = old.t;
      event.old_index = matches[c].keyframe;
      event.old_from_map = matches[c].keyframe < map_keyframes_;
      event.score = matches[c].score;
      event.check = check;
      event.relative = newest.body.inverse() * check.old_body;
    }
    if (check.accepted) break;
  }
  return event;
}

void LoopDetector::checkDrift(size_t old_index, LoopCheck& check) const {
  const Eigen::Isometry3d& odometry = keyframes_[old_index].body;
  const double path = path_.back() - path_[old_index];
  const double moved = (check.old_body.translation() - odometry.translation()).norm();
  const Eigen::Matrix3d turn = odometry.linear().transpose() * check.old_body.linear();
  const double yaw_deg = std::abs(std::atan2(turn(1, 0), turn(0, 0))) * 180 / M_PI;
  if (moved <= options_.loop_max_drift_m + options_.loop_max_drift_ratio * path &&
      yaw_deg <= options_.loop_max_yaw_drift_deg)
    return;
  char why[96];
  std::snprintf(why, sizeof why, "drift %.2f m, %.1f deg over %.1f m of path", moved, yaw_deg,
                path);
  check.accepted = false;
  check.why = why;
}

void LoopDetector::addMapKeyframes(std::vector<StoredKeyframe> keyframes) {
  if (!keyframes_.empty()) throw std::logic_error("LoopDetector: map keyframes come first");
  keyframes_ = std::move(keyframes);
  map_keyframes_ = keyframes_.size();
  path_.assign(map_keyframes_, 0.0);
  clearSession();
}

void LoopDetector::clearSession() {
  keyframes_.resize(map_keyframes_);
  path_.resize(map_keyframes_);
  database_.clear();
  vocabulary_ = BinaryVocabulary();
  next_training_ = 0;
  if (map_keyframes_ == 0) return;
  trainVocabulary();
  next_training_ = 2 * map_keyframes_;
}

}  // namespace rpvio
