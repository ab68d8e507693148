#pragma once
// Revisits among the keyframes that left the window: a bag-of-words query (binary_vocabulary.h)
// over the keyframes older than `loop_min_age_s`, then the geometric check (loop_verification.h)
// of the best candidates. The vocabulary is trained on the run's own keyframes, when
// `loop_vocabulary_keyframes` of them are stored and again each time their number doubles (the
// stored vectors are then recomputed): no vocabulary file, and words fitted to the place revisited.
// Keyframes of a loaded map (keyframe_map_file.h) come first: they are candidates whatever their
// time, and the vocabulary is trained on them at once.
#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "common/options.h"
#include "mrpt_modules/loop/keyframe_database.h"
#include "mrpt_modules/loop/loop_verification.h"

namespace rpvio {

struct LoopDetectorOptions {
  int loop_corners = 500;             // ORB corners per keyframe
  double loop_min_age_s = 20;         // s: a candidate is at least this much older
  double loop_min_score_ratio = 0.3;  // of the query's score with the previous keyframe
  int loop_candidates = 3;            // geometric checks per query, best score first
  // Within a run, the odometry's drift between the two keyframes bounds where the check may place
  // the old one: within loop_max_drift_m + loop_max_drift_ratio × the path flown between them of
  // where the odometry has it, and within loop_max_yaw_drift_deg of its yaw.
  double loop_max_drift_m = 1.0;
  double loop_max_drift_ratio = 0.05;
  double loop_max_yaw_drift_deg = 15;
  // A revisit farther than this from the old keyframe is not used: the PnP's error grows with the
  // distance to the points (0: any distance).
  double loop_max_baseline_m = 3;
  size_t loop_vocabulary_keyframes = 40;       // first training
  size_t loop_vocabulary_descriptors = 50000;  // at most, evenly sampled, per training
  LoopCheckOptions check;
  VocabularyOptions vocabulary;

  template <class Visitor>
  void fields(Visitor& v) {
    RPVIO_OPTION(v, loop_corners);
    RPVIO_OPTION(v, loop_min_age_s);
    RPVIO_OPTION(v, loop_min_score_ratio);
    RPVIO_OPTION(v, loop_candidates);
    RPVIO_OPTION(v, loop_max_drift_m);
    RPVIO_OPTION(v, loop_max_drift_ratio);
    RPVIO_OPTION(v, loop_max_yaw_drift_deg);
    RPVIO_OPTION(v, loop_max_baseline_m);
    RPVIO_OPTION(v, loop_vocabulary_keyframes);
    RPVIO_OPTION(v, loop_vocabulary_descriptors);
    check.fields(v);
  }
};

/// A revisit found by appearance, and what the geometric check made of it.
struct LoopEvent {
  double t = 0;          // the query keyframe
  double t_old = 0;      // the candidate it was matched with (the best one when all were rejected)
  size_t old_index = 0;  // the candidate's index among the stored keyframes
  bool old_from_map = false;  // the candidate is a keyframe of the loaded map
  double score = 0;           // bowScore of the two
  LoopCheck check;
  // The old keyframe's body seen from the query's (accepted checks): the revisit's measurement.
  Eigen::Isometry3d relative = Eigen::Isometry3d::Identity();
};

class LoopDetector {
 public:
  explicit LoopDetector(const LoopDetectorOptions& options, const Eigen::Isometry3d& T_BC)
      : options_(options), T_BC_(T_BC) {}

  /// Stores a keyframe (body pose in the world) and looks for its revisit; the event when a
  /// candidate passed the appearance test (accepted or not).
  std::optional<LoopEvent> add(double t, const Eigen::Isometry3d& body,
                               KeyframeAppearance appearance);
  /// Stores the keyframes of a loaded map (before any add()) and trains the vocabulary on them.
  void addMapKeyframes(std::vector<StoredKeyframe> keyframes);
  /// Forgets the keyframes add() stored, not the map's (the odometry re-initialized in another
  /// world).
  void clearSession();
  size_t keyframes() const { return keyframes_.size(); }
  size_t mapKeyframes() const { return map_keyframes_; }
  /// Every keyframe stored, the map's first.
  const std::vector<StoredKeyframe>& stored() const { return keyframes_; }
  int vocabularyWords() const { return vocabulary_.words(); }

 private:
  void trainVocabulary();
  std::optional<LoopEvent> query(const BowVector& bow);

  LoopDetectorOptions options_;
  Eigen::Isometry3d T_BC_;
  /// Rejects an accepted check of a run's keyframe that moves the old keyframe farther than the
  /// odometry can have drifted (a wrong PnP on repeated texture or moving people).
  void checkDrift(size_t old_index, LoopCheck& check) const;

  std::vector<StoredKeyframe> keyframes_;
  std::vector<double> path_;  // the odometry's path length at each keyframe (the map's: 0)
  size_t map_keyframes_ = 0;  // the first ones
  BinaryVocabulary vocabulary_;
  KeyframeDatabase database_;
  size_t next_training_ = 0;  // keyframes at the next training; 0: the first
};

}  // namespace rpvio
