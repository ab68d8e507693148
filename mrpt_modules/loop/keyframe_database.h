#pragma once
// The keyframes' bag-of-words vectors with an inverted index (word → keyframes holding it), so a
// query touches only the keyframes sharing a word with it.
#include <cstddef>
#include <unordered_map>
#include <vector>

#include "mrpt_modules/loop/binary_vocabulary.h"

namespace rpvio {

struct DatabaseMatch {
  size_t keyframe = 0;  // index in insertion order
  double score = 0;     // bowScore
};

class KeyframeDatabase {
 public:
  /// Adds the next keyframe's vector; its index is size() before the call.
  void add(const BowVector& bow);
  size_t size() const { return vectors_.size(); }
  const BowVector& vector(size_t keyframe) const { return vectors_[keyframe]; }
  /// Keyframes with index < `before` and a score >= `min_score`, best first (ties: older first).
  std::vector<DatabaseMatch> query(const BowVector& bow, size_t before, double min_score) const;
  void clear();

 private:
  struct Posting {
    size_t keyframe;
    double weight;
  };
  std::vector<BowVector> vectors_;
  std::unordered_map<int, std::vector<Posting>> inverted_;
};

}  // namespace rpvio
